#include "pipeline/render_messages.h"

#include <algorithm>
#include <cstdio>

#include "config/duration.h"

namespace sl {

void print_render_start(const RenderContext& ctx, const SceneDesc& scene, const MemoryPlan& plan, const RankExchange* ex) {
    std::fprintf(stderr, "slowlight: %dx%d, %d frames, %d passes x %lld photons, %d section%s%s; buckets %s per section%s, about %s fixed\n",
                 ctx.width, ctx.height, scene.time.frames, scene.render.passes,
                 static_cast<long long>(scene.render.photons_per_pass), plan.sections, plan.sections > 1 ? "s" : "",
                 plan.overlap ? " (two alive: encode while rendering)" : "",
                 format_bytes(plan.buffer_bytes_per_section).c_str(),
                 ex ? (" per rank on " + std::to_string(ex->ranks()) + " MPI ranks").c_str() : "",
                 format_bytes(plan.fixed_overhead_bytes).c_str());
}

void print_after_render(const PipelineStats& stats, const SceneDesc& scene, const MemoryPlan& plan,
                        const RunOptions& o, const TimeBudget& budget, const std::string& resumed_from,
                        const RankExchange* ex) {
    if (ex)
        std::fprintf(stderr, "slowlight: %d MPI ranks; rank 0 received %s with the passes (%s per pass per rank) and %s of frames\n",
                     ex->ranks(), format_bytes(stats.exchanged_received[0]).c_str(),
                     format_bytes(stats.exchanged_received[0] / static_cast<uint64_t>(std::max(1, stats.passes_run))).c_str(),
                     format_bytes(stats.exchanged_received[1]).c_str());
    if (stats.sections_resumed > 0)
        std::fprintf(stderr, "slowlight: resumed %d of %d sections from %s\n", stats.sections_resumed, plan.sections,
                     resumed_from.c_str());
    if (budget.limited() && !stats.interrupted) {
        int reached = budget.passes().value_or(scene.render.passes);
        int fewest = reached;  // a later section is cut short only when the run went well past the budget
        for (int n : stats.passes_per_section)
            if (n > 0) fewest = std::min(fewest, n);
        std::fprintf(stderr, "slowlight: time limit %s: %d pass%s per section (--passes %d)%s\n",
                     format_duration(*o.time_limit).c_str(), reached, reached == 1 ? "" : "es", scene.render.passes,
                     fewest < reached ? ("; a later section was cut at " + std::to_string(fewest) +
                                         " passes: the run had gone a quarter past the budget")
                                            .c_str()
                                      : "");
    }
}

std::string what_was_written(const PipelineStats& stats, const FrameOutputs& outputs, const RunOptions& o, int passes) {
    if (outputs.frames_written == 0) return "nothing written";
    std::string where;
    auto add = [&](const std::string& w) { where += (where.empty() ? "" : ", ") + w; };
    if (!o.output.empty()) add(o.output == "-" ? std::string("stdout") : o.output);
    if (!o.exr_dir.empty()) add(o.exr_dir + "/");
    if (!o.png_dir.empty()) add(o.png_dir + "/");
    std::string text = "wrote frames 0-" + std::to_string(outputs.frames_written - 1);
    if (stats.interrupted_section >= 0)
        text += " (section " + std::to_string(stats.interrupted_section + 1) + " from " +
                std::to_string(stats.passes_per_section[stats.interrupted_section]) + " of " + std::to_string(passes) +
                " passes)";
    return text + (where.empty() ? " (to no output: none was asked for)" : " to " + where);
}

void print_interrupted(const PipelineStats& stats, const MemoryPlan& plan, const FrameOutputs& outputs,
                       const RunOptions& o, int passes, bool checkpoints, const std::string& again) {
    std::string where = stats.interrupted_section >= 0
                            ? "in section " + std::to_string(stats.interrupted_section + 1) + "/" + std::to_string(plan.sections)
                            : std::string("before a section's first pass");
    std::fprintf(stderr, "slowlight: interrupted %s; %s\n", where.c_str(), what_was_written(stats, outputs, o, passes).c_str());
    if (checkpoints)
        std::fprintf(stderr, "slowlight: %s; to continue: %s\n",
                     stats.interrupted_checkpoint.empty() ? ("finished frames are in " + o.exr_dir).c_str()
                                                          : ("state saved in " + stats.interrupted_checkpoint).c_str(),
                     again.c_str());
    else
        std::fprintf(stderr, "slowlight: nothing saved to resume from (give --checkpoint DIR or --exr-dir to make a "
                             "render resumable)\n");
}

void print_final_line(const FrameOutputs& outputs, const std::string& stats_path,
                      std::chrono::steady_clock::time_point t0) {
    std::string what = outputs.summary();
    if (!stats_path.empty()) what += (what.empty() ? "" : ", ") + stats_path + " (statistics)";
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "slowlight: wrote %s in %.1f s\n", what.c_str(), seconds);
}

std::string steady_black_warning(const SceneDesc& scene) {
    return "warning: " + scene.source +
           ": no light reached the camera except straight from the lights: every frame is black "
           "but for them (are the lights pointing away, or outside the room? see slowlight info)";
}

}  // namespace sl
