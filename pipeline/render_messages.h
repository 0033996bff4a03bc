#pragma once
// The lines `slowlight render` prints on stderr about the render itself: what it is about to
// do, what happened (ranks, resumed sections, the time limit's passes), what an interrupt
// left behind, and the last line. Only rank 0 speaks for the job.
#include <chrono>
#include <string>

#include "config/run_options.h"
#include "config/scene_desc.h"
#include "pipeline/frame_outputs.h"
#include "pipeline/memory_plan.h"
#include "pipeline/render_pipeline.h"
#include "pipeline/time_budget.h"
#include "stages/render/rank_exchange.h"
#include "stages/render/render_context.h"

namespace sl {

// "slowlight: 256x256, 48 frames, 64 passes x 100000 photons, 1 section; buckets ..."
void print_render_start(const RenderContext& ctx, const SceneDesc& scene, const MemoryPlan& plan, const RankExchange* ex);

// After the passes: the ranks' traffic, the sections resumed (from `resumed_from`), and the
// passes --time-limit reached.
void print_after_render(const PipelineStats& stats, const SceneDesc& scene, const MemoryPlan& plan,
                        const RunOptions& o, const TimeBudget& budget, const std::string& resumed_from,
                        const RankExchange* ex);

// "wrote frames 0-23 (section 2 from 12 of 64 passes) to out.mp4, exr/"
std::string what_was_written(const PipelineStats& stats, const FrameOutputs& outputs, const RunOptions& o, int passes);

// Where an interrupt stopped, what was written and how to continue (`again`: the command that
// resumes, when `checkpoints` were kept).
void print_interrupted(const PipelineStats& stats, const MemoryPlan& plan, const FrameOutputs& outputs,
                       const RunOptions& o, int passes, bool checkpoints, const std::string& again);

// "warning: SCENE: no light reached the camera ...": every frame is black but for the emitters.
std::string steady_black_warning(const SceneDesc& scene);

// The last line of a run: what was written, how many frames, how long it took.
void print_final_line(const FrameOutputs& outputs, const std::string& stats_path,
                      std::chrono::steady_clock::time_point t0);

}  // namespace sl
