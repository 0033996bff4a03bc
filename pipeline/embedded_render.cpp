#include "pipeline/embedded_render.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <chrono>

#include "config/command_line.h"
#include "config/parse_scene.h"
#include "foundation/errors.h"
#include "foundation/warning_lines.h"
#include "pipeline/render_command.h"
#include "pipeline/render_messages.h"
#include "pipeline/render_setup.h"
#include "pipeline/run_stats.h"
#include "pipeline/scene_checks.h"

namespace sl {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

RunOptions embedded_options(const std::string& command, const std::vector<std::string>& args) {
    std::vector<const char*> argv{"slowlight", command.c_str()};
    for (const std::string& a : args) argv.push_back(a.c_str());
    return parse_command_line(static_cast<int>(argv.size()), argv.data());
}

SceneDesc embedded_scene(const RunOptions& o, const std::optional<SceneText>& text) {
    if (!text) return load_scene(o);
    if (!o.scene_path.empty())
        throw InputError("command line: a scene given as a dict cannot also name the scene file " + o.scene_path);
    SceneDesc scene = parse_scene_text(text->json, text->source_name, text->base_dir);
    complete_scene(scene, o);
    return scene;
}

EmbeddedRender::EmbeddedRender(const std::vector<std::string>& args, const std::optional<SceneText>& text) {
    const Clock::time_point t0 = Clock::now();
    o_ = embedded_options("render", args);
    check_rank_options(o_, nullptr);
    {
        ScopedWarningSink imports([this](const std::string& line) { warnings_.push_back(line); });
        scene_ = embedded_scene(o_, text);
    }
    plan_ = plan_memory(scene_, o_);
    check_fits_machine(plan_);
    ctx_ = std::make_unique<RenderContext>(scene_);
    for (const std::string& w : scene_warnings(*ctx_, scene_facts(*ctx_))) warnings_.push_back(w);
    setup_seconds_ = since(t0);
}

PipelineStats EmbeddedRender::run(FrameSink& sink, const ProgressFn& progress, const std::atomic<bool>& cancel) {
    const Clock::time_point t0 = Clock::now();
    std::unique_ptr<tbb::global_control> threads;
    if (o_.threads > 0)
        threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o_.threads);
    if (o_.exposure) {
        ExposurePlan fixed;
        fixed.base = *o_.exposure;
        sink.set_exposure_plan(fixed);
    }
    PipelineJob job;
    job.ctx = ctx_.get();
    job.plan = plan_;
    job.strategy = o_.strategy;
    job.exposure_rule.percentile = o_.exposure_percentile;
    job.exposure_rule.follow = o_.exposure_follow;
    job.log = [](const std::string&) {};  // the caller has the numbers (stats) instead of lines
    PipelineStats stats = run_pipeline(job, sink, progress, cancel);
    if (stats.steady_black && !stats.interrupted) warnings_.push_back(steady_black_warning(scene_));
    wall_seconds_ = setup_seconds_ + since(t0);
    return stats;
}

nlohmann::json EmbeddedRender::stats(const PipelineStats& stats, double exposure) const {
    RunSummary summary;
    summary.scene = &scene_;
    summary.plan = plan_;
    summary.pipeline = stats;
    summary.setup_seconds = setup_seconds_;
    summary.exposure = exposure;
    summary.strategy = o_.strategy;
    summary.threads = o_.threads > 0 ? o_.threads : tbb::info::default_concurrency();
    summary.wall_seconds = wall_seconds_;
    return stats_json(summary);
}

}  // namespace sl
