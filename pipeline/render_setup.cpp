#include "pipeline/render_setup.h"

#include <filesystem>
#include <system_error>

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
