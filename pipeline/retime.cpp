#include "pipeline/retime.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "config/command_line.h"
#include "config/input_file.h"
#include "config/json_reader.h"
#include "config/limits.h"
#include "config/parse_scene.h"
#include "config/pulse_width.h"
#include "config/text_util.h"
#include "foundation/errors.h"
#include "pipeline/frame_outputs.h"
#include "pipeline/output_checks.h"
#include "stages/output/npy_cube.h"
#include "pipeline/exposure.h"

namespace sl {
namespace {

struct CubeInfo {
    double start_ns = 0, end_ns = 0, fps = 24;
    int frames = 0, width = 0, height = 0;
    std::vector<std::pair<int64_t, int64_t>> emitter_runs;  // pixels that see a light (none in older cubes)
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
    // A cube in mitransient's order holds the frames' bins only, pixel by pixel: not ours to retime.
    if (top.has("cube_layout") && top.string("cube_layout") != "slowlight")
        top.fail("cube_layout", "retime reads cubes in slowlight's order (render --cube without --cube-layout "
                                "mitransient), got '" + printable(top.string("cube_layout")) + "'");
    c.start_ns = top.number("start_ns", Range::any());
    c.end_ns = top.number("end_ns", Range::any());
    c.fps = top.number("fps", Range::closed(limits::kMinFps, limits::kMaxFps));
    c.frames = static_cast<int>(top.integer("frames", 1, limits::kMaxFrames));
    c.width = static_cast<int>(top.integer("width", 1, limits::kMaxImageSide));
    c.height = static_cast<int>(top.integer("height", 1, limits::kMaxImageSide));
    if (top.has("emitter_pixels")) {  // runs [first pixel, count] of pixels that see a light
        const Json& runs = top.at("emitter_pixels");
        const int64_t pixels = int64_t(c.width) * c.height;
        bool ok = runs.is_array();
        for (size_t i = 0; ok && i < runs.size(); ++i) {
            const Json& run = runs[i];
            ok = run.is_array() && run.size() == 2 && run[0].is_number_integer() && run[1].is_number_integer();
            if (!ok) break;
            const int64_t first = run[0].get<int64_t>(), count = run[1].get<int64_t>();
            ok = first >= 0 && count >= 0 && first <= pixels && count <= pixels - first;
            if (ok) c.emitter_runs.emplace_back(first, count);
        }
        if (!ok) top.fail("emitter_pixels", "must be a list of [first pixel, count] runs inside the image");
    }
    if (!Timeline{c.start_ns, c.end_ns, c.frames}.has_valid_delta())
        top.fail("end_ns", "must be greater than start_ns (" + format_number(c.start_ns) + "), got " +
                               format_number(c.end_ns));
    return c;
}

}  // namespace

int retime(const RunOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    // The command line has refused every option retime does not use.
    const RenderOverrides& ov = o.overrides;

    check_outputs(outputs_of(o), {o.scene_path, o.scene_path + ".json"});
    NpyCube cube = read_npy_cube(o.scene_path);
    CubeInfo info = read_sidecar(o.scene_path);  // refuses a cube in mitransient's order
    if (cube.planes != info.frames + 2 || cube.width != info.width || cube.height != info.height)
        throw InputError(o.scene_path + ": the array's shape does not match its side-car file");
    require_an_output(o);

    EmissionDesc emission;
    if (ov.emission) emission = parse_emission_option(*ov.emission);
    // The same whole-frames check as a scene's pulse width, against the cube's timeline.
    const TimeDesc time{info.start_ns, info.end_ns, info.frames, info.fps};
    if (auto problem = check_pulse_width(time, emission)) command_line_error("--emission", *problem);
    const Timeline timeline{info.start_ns, info.end_ns, info.frames,
                            emission.mode == EmissionMode::Pulse ? emission.width_frames : 1};

    const size_t pixels = static_cast<size_t>(cube.width) * cube.height, values = pixels * 3;
    std::vector<float> steady(values, 0.0f);
    for (int p = 0; p < cube.planes; ++p)
        for (size_t i = 0; i < values; ++i) steady[i] += cube.plane(p)[i];

    OutputSettings out;
    out.video = o.output;
    out.exr_dir = o.exr_dir;
    out.png_dir = o.png_dir;
    out.width = cube.width;
    out.height = cube.height;
    out.fps = info.fps;
    out.timeline = timeline;
    out.exposure = o.exposure;
    out.tone = o.tone;
    out.label_time = o.label_time;
    out.metadata = {{"slowlight:retimed_from", o.scene_path}};
    FrameOutputs outputs(out);

    // Frame k of the video being made (constant: a running sum; pulse: its m buckets).
    std::vector<double> running(values, 0.0);
    std::vector<float> frame(values);
    auto make_frame = [&](int k) {
        if (k == 0)
            for (size_t i = 0; i < values; ++i) running[i] = cube.plane(0)[i];
        if (emission.mode == EmissionMode::Constant) {
            for (size_t i = 0; i < values; ++i) frame[i] = static_cast<float>(running[i] += cube.plane(k + 1)[i]);
        } else {
            // Plane j + 1 holds bucket j; the pulse frame k sums buckets k - m + 1 .. k.
            std::fill(frame.begin(), frame.end(), 0.0f);
            for (int j = std::max(0, k - timeline.pulse_buckets + 1); j <= k; ++j)
                for (size_t i = 0; i < values; ++i) frame[i] += cube.plane(j + 1)[i];
        }
    };

    // The exposure render would choose for this video: the same statistic, the same pixels left out.
    if (outputs.needs_exposure()) {
        ExposureRule rule;
        rule.percentile = o.exposure_percentile;
        rule.follow = o.exposure_follow;
        ExposureMeter meter(emission.mode, rule, mask_from_runs(info.emitter_runs, pixels));
        meter.add_steady(steady.data(), pixels);
        if (meter.wants_frames())
            for (int k = 0; k < info.frames; ++k) {
                make_frame(k);
                meter.add_frame(k, frame.data(), pixels);
            }
        outputs.set_exposure_plan(meter.decide());
    }
    outputs.write_steady(steady);
    for (int k = 0; k < info.frames; ++k) {
        make_frame(k);
        outputs.write_frame(k, frame);
    }
    outputs.finish();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "slowlight: wrote %s in %.1f s\n", outputs.summary().c_str(), seconds);
    return 0;
}

}  // namespace sl
