#include "pipeline/render_frames.h"

#include <atomic>

namespace sl {

PipelineStats render_frames(const RenderContext& ctx, const RenderRequest& request, FrameSink& sink) {
    PipelineJob job;
    job.ctx = &ctx;
    job.strategy = request.strategy;
    job.plan.sections = request.strategy == Strategy::FrameByFrame ? ctx.timeline.frames : request.sections;
    job.plan.overlap = false;
    job.passes = request.passes;
    job.photons_per_pass = request.photons_per_pass;
    job.check_black = false;                 // no warning to give
    job.log = [](const std::string&) {};  // quiet: the caller reports what it needs
    std::atomic<bool> never{false};
    return run_pipeline(job, sink, {}, never);
}

}  // namespace sl
