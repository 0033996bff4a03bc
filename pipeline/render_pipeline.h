#pragma once
// The streaming frame pipeline, a TBB flow graph over sections and frames, into a frame sink
// (the program's FrameOutputs, or images in memory through render_frames.h):
//
//   sections -> limiter(1 or 2 alive) -> render section (its own pass graph)
//            -> in section order -> split into frames -> queue -> limiter(2 frames) -> assemble
//            -> in frame order -> write
//                                                 ^ frame done        section done v
//
// Frames leave in order. A section's time buckets are freed as soon as its last frame is
// written; with two sections alive the next section renders while this one is encoded.
// Interrupted, the pass in flight finishes, the section in progress is saved (checkpoint) and
// every one of its frames is assembled from the passes completed and written after the
// finished sections; sections that never started are not written.
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "config/run_options.h"
#include "pipeline/exposure.h"
#include "pipeline/frame_outputs.h"
#include "pipeline/frame_sink.h"
#include "pipeline/checkpoint.h"
#include "pipeline/memory_plan.h"
#include "pipeline/preview_sheet.h"
#include "pipeline/resume_checkpoints.h"
#include "pipeline/section_plan.h"
#include "pipeline/time_budget.h"
#include "stages/render/render_context.h"
#include "stages/render/section_renderer.h"

namespace sl {

struct PipelineStats {
    StageTimes render;
    RenderCounts counts;  // every pass's photons and rays, the exposure preview's included (this rank's)
    double exposure_pass = 0, assembly = 0, writing = 0;
    double buffers = 0;  // allocating the sections' time buckets and first touching their pages
    uint64_t photons = 0, rays = 0, photon_records = 0, photon_map_bytes = 0;  // totals of `counts`
    int sections_done = 0, sections_resumed = 0;
    int passes_run = 0;  // photon passes traced, the exposure preview's included
    bool interrupted = false;
    // With several ranks (MPI): their number, and this rank's payload bytes per channel
    // (0: the passes' photons and reductions, 1: frames to rank 0), counted before the totals.
    int ranks = 1;
    uint64_t exchanged_sent[2] = {0, 0}, exchanged_received[2] = {0, 0};
    double photon_transfer_seconds = 0;  // rank 0's time moving photon records (not waiting)
    bool steady_black = false;  // nothing but the emitters themselves reached the camera
    std::vector<int> passes_per_section;  // passes each section's frames got (0: not written)
    int interrupted_section = -1;         // the section written from the passes it had, if any
    std::string interrupted_checkpoint;   // where that section's state was saved ("" if nowhere)
};

// (section, passes done in it) after every pass.
using ProgressFn = std::function<void(int section, int pass)>;

struct PipelineJob {
    const RenderContext* ctx = nullptr;
    MemoryPlan plan;
    Strategy strategy = Strategy::Single;
    int passes = 0;                // per section; 0: the scene's
    int64_t photons_per_pass = 0;  // 0: the scene's
    std::vector<bool> on_disk;  // per section: already rendered (--resume)
    const FrameOutputs* exr_files = nullptr;  // where on_disk's frames are read back (and --exr-dir)
    ExposureRule exposure_rule;
    std::string fingerprint;    // of this render's settings: resumed frames must carry it
    bool check_black = true;    // find PipelineStats::steady_black (the program warns of it)
    std::vector<SectionStart> starts;  // per section: a checkpoint to continue from (--resume)
    Checkpointer* checkpointer = nullptr;  // saves the section in progress; null: never
    TimeBudget* budget = nullptr;          // --time-limit; null: none
    PreviewSheet* preview = nullptr;       // --preview; null: none
    std::function<void(const std::string&)> log;               // one line for stderr
    std::function<void(int section, int passes_done)> section_started;
    std::function<void(double seconds, int passes)> full_pass_seconds;  // the preview's mean pass
    std::function<void(int passes)> passes_fixed;              // --time-limit decided the passes
    std::function<void(int frame)> frame_assembled;  // after each frame's assembly (tests delay it)
};

PipelineStats run_pipeline(const PipelineJob& job, FrameSink& outputs, const ProgressFn& progress,
                           const std::atomic<bool>& cancel);

}  // namespace sl
