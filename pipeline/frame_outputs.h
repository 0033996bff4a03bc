#pragma once
// Where finished frames go: linear EXR files, tone-mapped PNGs, the video encoder and the
// transient cube. All of them are opened (and checked) before rendering starts.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stages/output/npy_cube.h"
#include "stages/output/video_encoder.h"

namespace sl {

struct OutputSettings {
    std::string video;  // "" for none, "-" for stdout
    std::string exr_dir, png_dir;
    std::string cube;   // "" for none
    int width = 0, height = 0, frames = 0;
    double fps = 24, start_ns = 0, end_ns = 0;
    std::optional<double> exposure;              // fixed by the user
    std::map<std::string, std::string> metadata;  // stored in every EXR header
};

class FrameOutputs {
public:
    explicit FrameOutputs(const OutputSettings& settings);  // opens the encoder, makes dirs

    bool needs_exposure() const { return !exposure_ && (encoder_ || !settings_.png_dir.empty()); }
    void set_exposure(double e) { exposure_ = e; }
    std::optional<double> exposure() const { return exposure_; }
    bool wants_cube() const { return cube_ != nullptr; }

    // `on_disk`: the EXR is already there (a resumed section), so only the rest is written.
    // `extra`: more EXR header entries for this frame (e.g. the passes it got).
    using Metadata = std::map<std::string, std::string>;
    void write_frame(int index, const std::vector<float>& rgb, bool on_disk = false, const Metadata& extra = {});
    void write_steady(const std::vector<float>& rgb, const Metadata& extra = {});
    void write_cube_plane(const std::vector<float>& rgb);
    void finish();  // closes the video so that it plays, and the cube

    std::string exr_frame_path(int index) const;
    std::string exr_steady_path() const;
    const std::string& exr_dir() const { return settings_.exr_dir; }

    double seconds_exr = 0, seconds_png = 0, seconds_video = 0;
    int64_t frames_written = 0;

private:
    OutputSettings settings_;
    std::optional<double> exposure_;
    std::unique_ptr<VideoEncoder> encoder_;
    std::unique_ptr<NpyCubeWriter> cube_;
    std::vector<uint8_t> rgb8_;
};

}  // namespace sl
