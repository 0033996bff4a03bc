#include "pipeline/render_setup.h"

#include <cstdio>
#include <filesystem>
#include <system_error>

#include "config/text_util.h"
#include "foundation/errors.h"
#include "pipeline/exposure.h"
#include "pipeline/resume.h"

namespace sl {

void check_rank_options(RunOptions& o, RankExchange* ex) {
    if (ex) {
        if (o.ranks > 0 && o.ranks != ex->ranks())
            throw InputError("command line: --ranks " + std::to_string(o.ranks) + ": this render runs on " +
                             std::to_string(ex->ranks()) + " MPI ranks");
        o.ranks = ex->ranks();
    } else if (o.ranks > 1) {
        throw InputError("command line: --ranks " + std::to_string(o.ranks) +
                         ": a render on several ranks is started by an MPI launcher (mpirun -np N slowlight render ...); "
                         "--ranks is for info");
    }
}

void check_sensor_request(const SensorRequest& sensors, const Timeline& timeline, bool print) {
    if (sensors.gate_start_ns) {
        const double a = *sensors.gate_start_ns, b = a + *sensors.gate_width_ns;
        // Only the frames' bins are resolved in time: a gate must lie within them.
        const double slack = Timeline::kWholeTolerance * timeline.delta();
        if (a < timeline.start_ns - slack || b > timeline.end_ns + slack)
            throw InputError("command line: --gate " + format_number(a) + ":" + format_number(*sensors.gate_width_ns) +
                             ": the gate [" + format_number(a) + ", " + format_number(b) +
                             ") ns must lie within the time window [" + format_number(timeline.start_ns) + ", " +
                             format_number(timeline.end_ns) + ") ns");
    }
    const double nyquist_hz = 1e9 / (2 * timeline.delta());
    for (double f : sensors.phasor_hz)
        if (print && f > nyquist_hz)
            std::fprintf(stderr, "warning: --phasor %s: above 1/(2 x frame width) = %s, the frames' bins cannot resolve "
                                 "it (its phase aliases); use more frames or a lower frequency\n",
                         frequency_label(f).c_str(), frequency_label(nyquist_hz).c_str());
}

void check_preview_path(const std::string& path) {
    if (path.empty()) return;
    std::filesystem::path dir = std::filesystem::path(path).parent_path();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec) || !std::filesystem::is_directory(dir.empty() ? "." : dir, ec))
        throw RuntimeFailure("--preview " + path + ": cannot write there (" +
                             (std::filesystem::is_directory(path, ec) ? std::string("a directory")
                                                                      : "no directory " + dir.string()) +
                             ")");
}

OutputSettings output_settings(const RunOptions& o, const SceneDesc& scene, const RenderContext& ctx,
                               const std::string& fingerprint) {
    OutputSettings out;
    out.video = o.output;
    out.exr_dir = o.exr_dir;
    out.png_dir = o.png_dir;
    out.cube = o.cube_path;
    out.cube_layout = o.cube_layout;
    out.hdf5 = o.hdf5_path;
    out.sensors = o.sensors;
    out.integers = {{"seed", scene.render.seed},
                    {"passes", static_cast<uint64_t>(scene.render.passes)},
                    {"photons_per_pass", static_cast<uint64_t>(scene.render.photons_per_pass)},
                    {"camera_tof", scene.render.camera_tof ? 1u : 0u}};
    out.width = scene.camera.width;
    out.height = scene.camera.height;
    out.fps = scene.time.fps;
    out.timeline = ctx.timeline;
    out.exposure = o.exposure;
    out.tone = o.tone;
    out.label_time = o.label_time;
    if (!o.cube_path.empty()) out.emitter_runs = mask_runs(emitter_pixels(ctx));
    out.metadata = {{"slowlight:version", SLOWLIGHT_VERSION}, {"slowlight:scene", scene.source},
                    {kFingerprintKey, fingerprint}};
    return out;
}

// In --checkpoint DIR, or else in --exr-dir, where --resume looks anyway. With several ranks,
// rank 0 alone reads and writes them (docs/distributed.md).
CheckpointSettings checkpoint_settings(const RunOptions& o, const MemoryPlan& plan) {
    CheckpointSettings checkpoints;
    checkpoints.dir = !o.checkpoint_dir.empty() ? o.checkpoint_dir : o.exr_dir;
    checkpoints.flag = !o.checkpoint_dir.empty() ? "--checkpoint" : "--exr-dir";
    checkpoints.every = o.checkpoint_every.value_or(kDefaultCheckpointEvery);
    checkpoints.keep_finished = o.exr_dir.empty() && plan.sections > 1;
    return checkpoints;
}

SectionStateId section_state_id(const SceneDesc& scene, const RenderContext& ctx, const MemoryPlan& plan,
                                const std::string& fingerprint) {
    SectionStateId id;
    id.program_version = SLOWLIGHT_VERSION;
    id.fingerprint = fingerprint;
    id.sections = plan.sections;
    id.passes_target = scene.render.passes;
    id.width = ctx.width;
    id.height = ctx.height;
    return id;
}

}  // namespace sl
