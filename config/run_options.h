#pragma once
// What the command line asked for. Values that are also scene keys are optional overrides:
// an empty optional means "keep the scene's value".
#include <cstdint>
#include <optional>
#include <string>

#include "config/scene_desc.h"  // LightUnits
#include "config/sensor_options.h"

namespace sl {

// Single: one convergence gives every frame (in K sections when memory asks for them);
// FrameByFrame: every frame its own full convergence (the paper's baseline).
enum class Strategy { Single, FrameByFrame };
inline const char* strategy_name(Strategy s) { return s == Strategy::Single ? "single" : "frame-by-frame"; }

// The curve from exposed linear radiance to display values (before the sRGB encoding).
enum class ToneCurve { Linear, Filmic, Log };

struct RenderOverrides {
    std::optional<int> frames, passes, width, height, max_depth;
    std::optional<int64_t> photons;
    std::optional<uint64_t> seed;
    std::optional<bool> camera_tof;
    std::optional<std::string> emission;  // "constant" | "pulse" | "pulse:WIDTH_NS" (validated)
};

struct RunOptions {
    enum class Command { Render, Info, Retime, Help, Version };
    Command command = Command::Render;
    std::string help_topic;  // Help: "render", "info", "retime", or empty for everything
    std::string scene_path;  // empty: built-in default demo scene (retime: the cube file)
    std::string output;      // video path, "-" for YUV4MPEG2 on stdout; empty: no video
    bool output_given = false;
    std::string exr_dir, png_dir, stats_path;
    std::string cube_path;  // --cube: the time-resolved stack as a NumPy .npy file
    CubeLayout cube_layout = CubeLayout::Slowlight;  // --cube-layout
    std::string hdf5_path;  // --hdf5: the frames' bins in tal's layout (time first)
    SensorRequest sensors;  // --phasor, --gate, --first-arrival: images in --exr-dir
    bool resume = false;    // --resume: keep sections whose frames are already in --exr-dir
    std::optional<int> sections;
    std::optional<uint64_t> max_memory_bytes;  // the whole process
    std::optional<uint64_t> max_bucket_bytes;  // the time buckets alone
    std::optional<double> exposure;  // linear multiplier; default from the steady image
    std::optional<double> exposure_percentile;  // expose this percentile to white instead of the mean
    bool exposure_follow = false;    // per-frame exposure that follows the light's energy
    ToneCurve tone = ToneCurve::Linear;
    bool label_time = false;         // --label time
    Strategy strategy = Strategy::Single;
    int threads = 0;  // 0: all cores
    int ranks = 0;    // --ranks (info: plan for N MPI ranks); under MPI, the ranks running
    bool progress = true;  // shown only when stderr is a terminal
    // Never lose a long render (docs/checkpoints.md). checkpoint_dir empty: --exr-dir, if any.
    std::string checkpoint_dir;
    std::optional<double> checkpoint_every;  // seconds; < 0: only at an interrupt
    std::optional<double> time_limit;        // seconds of wall time for the whole run
    std::string preview_path;                // --preview FILE.png: contact sheet while rendering
    RenderOverrides overrides;
    // --gltf-light-units: how glTF files read their lights' intensities, unless their scene entry
    // says (its "light_units"); applied before the files are read (pipeline/render_command.cpp).
    std::optional<LightUnits> gltf_light_units;
    // --gltf-principled: how glTF files' metallic-roughness materials draw their diffuse base,
    // unless their scene entry says (its "principled"); applied before the files are read.
    std::optional<PrincipledBase> gltf_principled;
};

}  // namespace sl
