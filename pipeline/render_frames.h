#pragma once
// The one in-process render: plan the sections -> render each (its passes) -> assemble its
// frames -> hand them, in order, to a frame sink. The program, the tests, the benchmarks and
// the report all render through it (the program through run_pipeline, with its checkpoints,
// exposure and --resume; the others through render_frames, which leaves those out).
#include <cstdint>

#include "config/run_options.h"
#include "pipeline/frame_sink.h"
#include "pipeline/render_pipeline.h"
#include "stages/render/render_context.h"

namespace sl {

struct RenderRequest {
    Strategy strategy = Strategy::Single;
    int sections = 1;               // Single: the timeline in this many sections; FrameByFrame: one per frame
    int passes = 0;                 // 0: the scene's
    int64_t photons_per_pass = 0;   // 0: the scene's
};

// One section at a time, nothing written, no exposure decided (the sink is asked for none).
PipelineStats render_frames(const RenderContext& ctx, const RenderRequest& request, FrameSink& sink);

}  // namespace sl
