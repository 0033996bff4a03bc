#include "pipeline/retime.h"

#include <cmath>

#include "config/input_file.h"
#include "config/json_reader.h"
#include "config/limits.h"
#include "config/parse_scene.h"
#include "config/text_util.h"
#include "core/errors.h"
#include "pipeline/frame_outputs.h"
#include "pipeline/output_checks.h"
#include "stages/output/npy_cube.h"
#include "stages/output/tone_map.h"

namespace sl {
namespace {

struct CubeInfo {
    double start_ns = 0, end_ns = 0, fps = 24;
    int frames = 0, width = 0, height = 0;
};

CubeInfo read_sidecar(const std::string& cube_path) {
    const std::string path = cube_path + ".json";
    std::string text;
    try {
        text = read_input_file(path, uint64_t(1) << 20, path, "cube side-car file");
    } catch (const InputError& e) {
        throw InputError(std::string(e.what()) + " (written by render --cube)");
    }
    // The same reader and ranges as a scene's keys: every message names this file and the key.
    Json j = parse_json_text(text, path);
    JsonObject top(j, "", path);
    CubeInfo c;
    c.start_ns = top.number("start_ns", Range::any());
    c.end_ns = top.number("end_ns", Range::any());
    c.fps = top.number("fps", Range::closed(limits::kMinFps, limits::kMaxFps));
    c.frames = static_cast<int>(top.integer("frames", 1, limits::kMaxFrames));
    c.width = static_cast<int>(top.integer("width", 1, limits::kMaxImageSide));
    c.height = static_cast<int>(top.integer("height", 1, limits::kMaxImageSide));
    if (!(c.end_ns > c.start_ns) || !std::isfinite((c.end_ns - c.start_ns) / c.frames))
        top.fail("end_ns", "must be greater than start_ns (" + format_number(c.start_ns) + "), got " +
                               format_number(c.end_ns));
    return c;
}

void refuse(bool given, const char* flag) {
    if (given) throw InputError(std::string("command line: ") + flag + " does not apply to retime");
}

}  // namespace

int retime(const RunOptions& o) {
    const RenderOverrides& ov = o.overrides;
    refuse(ov.frames.has_value(), "--frames");
    refuse(ov.passes.has_value(), "--passes");
    refuse(ov.photons.has_value(), "--photons");
    refuse(ov.width.has_value() || ov.height.has_value(), "--width/--height");
    refuse(o.sections.has_value() || o.max_memory_bytes.has_value(), "--sections/--max-memory");
    refuse(!o.cube_path.empty() || o.resume, "--cube/--resume");

    check_outputs(outputs_of(o), {o.scene_path, o.scene_path + ".json"});
    NpyCube cube = read_npy_cube(o.scene_path);
    CubeInfo info = read_sidecar(o.scene_path);
    if (cube.planes != info.frames + 2 || cube.width != info.width || cube.height != info.height)
        throw InputError(o.scene_path + ": the array's shape does not match its side-car file");

    EmissionDesc emission;
    if (ov.emission) emission = parse_emission_option(*ov.emission);
    const double delta = (info.end_ns - info.start_ns) / info.frames;
    int width_buckets = 1;
    if (emission.mode == EmissionMode::Pulse && emission.width_ns > 0) {
        double m = emission.width_ns / delta;
        if (std::abs(m - std::round(m)) > 1e-6 * m || std::round(m) < 1)
            throw InputError("command line: --emission: the pulse width must be a multiple of the bucket width " +
                             std::to_string(delta) + " ns");
        width_buckets = static_cast<int>(std::round(m));
    }

    const size_t values = static_cast<size_t>(cube.width) * cube.height * 3;
    std::vector<float> steady(values, 0.0f);
    for (int p = 0; p < cube.planes; ++p)
        for (size_t i = 0; i < values; ++i) steady[i] += cube.plane(p)[i];

    OutputSettings out;
    out.video = o.output;
    out.exr_dir = o.exr_dir;
    out.png_dir = o.png_dir;
    out.width = cube.width;
    out.height = cube.height;
    out.frames = info.frames;
    out.fps = info.fps;
    out.start_ns = info.start_ns;
    out.end_ns = info.end_ns;
    out.exposure = o.exposure;
    out.metadata = {{"slowlight:retimed_from", o.scene_path}};
    FrameOutputs outputs(out);
    if (outputs.needs_exposure()) outputs.set_exposure(exposure_from_steady(steady.data(), cube.width, cube.height));
    outputs.write_steady(steady);

    std::vector<double> running(values, 0.0);
    for (size_t i = 0; i < values; ++i) running[i] = cube.plane(0)[i];
    std::vector<float> frame(values);
    for (int k = 0; k < info.frames; ++k) {
        if (emission.mode == EmissionMode::Constant) {
            for (size_t i = 0; i < values; ++i) frame[i] = static_cast<float>(running[i] += cube.plane(k + 1)[i]);
        } else {
            // Plane j + 1 holds bucket j; the pulse frame k sums buckets k - m + 1 .. k.
            std::fill(frame.begin(), frame.end(), 0.0f);
            for (int j = std::max(0, k - width_buckets + 1); j <= k; ++j)
                for (size_t i = 0; i < values; ++i) frame[i] += cube.plane(j + 1)[i];
        }
        outputs.write_frame(k, frame);
    }
    outputs.finish();
    return 0;
}

}  // namespace sl
