#pragma once
// One run_pipeline call: the state its stages share (the job, the sink, the counters, the frame
// carried between sections) and each stage as a named step. Internal to the pipeline room:
// render_pipeline.cpp wires the steps into the flow graph, section_stage.cpp renders a section,
// frame_stages.cpp assembles and writes its frames.
#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/frame_buffer_pool.h"
#include "pipeline/render_pipeline.h"
#include "stages/render/frame_assembly.h"

namespace sl {

struct Section {
    SectionLayout layout;
    bool last = false;
    bool from_disk = false;  // resumed: its frames are read back from the EXR files
    bool complete = true;    // false when never started (or not one pass done): nothing written
    bool partial = false;    // interrupted: written from the passes it had
    int passes = 0;          // passes its frames got
    SectionRun run;
    std::optional<FrameAssembler> assembler;
};
using SectionPtr = std::shared_ptr<Section>;

struct FrameJob {
    SectionPtr section;
    int frame = 0;
};

struct FrameImage {
    SectionPtr section;
    int frame = 0;
    std::vector<float> rgb;
    std::vector<float> before, bucket, after;  // transient-cube planes, when asked for
    // With the last section's first frame: the steady image and, when none was fixed yet, the
    // exposure it gives. Only the write stage hands them to the outputs: the outputs' scratch
    // buffers (FrameOutputs::rgb8_) are the write stage's alone.
    std::vector<float> steady;
    std::optional<ExposurePlan> exposure;
};
// Frames travel by pointer: a flow-graph edge copies its message, and a frame is megabytes.
using FramePtr = std::shared_ptr<FrameImage>;

class PipelineRun {
public:
    PipelineRun(const PipelineJob& job, FrameSink& outputs, const ProgressFn& progress, const std::atomic<bool>& cancel);

    // The steps of run_pipeline, in order.
    void expose_before_frames();  // from disk or a preview, when no section can decide it itself
    void stream_sections();       // the flow graph: render -> split -> assemble -> write
    PipelineStats totals();       // this rank's counters, summed over the ranks

    // The stages (section_stage.cpp, frame_stages.cpp); each runs on one node of the graph.
    SectionPtr render_section(int index);
    FramePtr assemble(const FrameJob& job);
    bool write(FrameImage& frame);  // true: the frame ended its section (its buffers go back to the pool)
    bool stopped() const { return ex_ ? agreed_stop_.load() : cancel_.load(); }
    int sections() const { return plan_.sections; }

private:
    using Clock = std::chrono::steady_clock;
    static double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

    bool resumed(int s) const { return s < static_cast<int>(job_.on_disk.size()) && job_.on_disk[s]; }
    SectionStart start_of(int s) const { return s < static_cast<int>(job_.starts.size()) ? job_.starts[s] : SectionStart{}; }
    void log(const std::string& line) const;
    void whole_image(std::vector<float>& rgb) const;  // with ranks: gathered to rank 0

    // section_stage.cpp
    std::unique_ptr<SectionBuffer> section_buffer(Section& s, const SectionStart& start);
    void carry_from_disk(int index);
    bool run_passes(Section& s, const SectionStart& start, std::unique_ptr<SectionBuffer> buffer);
    void settle_section(Section& s, const SectionStart& start, bool by_interrupt);
    void count_section(const Section& s, const SectionStart& start);
    // frame_stages.cpp
    void decide_from_steady(Section& s, FrameImage& img);
    void free_section(Section& s);

    const PipelineJob& job_;
    const RenderContext& ctx_;
    const MemoryPlan& plan_;
    FrameSink& outputs_;
    const ProgressFn& progress_;
    const std::atomic<bool>& cancel_;
    PipelineStats stats_;
    const int passes_;
    const int64_t photons_per_pass_;
    const EmissionMode mode_;
    const std::vector<SectionLayout> layouts_;
    // With several ranks, every rank takes part in whatever rank 0's outputs need (the
    // exposure, the cube's planes), so rank 0 decides; the frames come to it, in order.
    RankExchange* ex_;
    const bool root_;
    bool exposure_pending_;
    bool wants_cube_;
    // An interrupt, as every rank sees it: with ranks, only once they agreed to stop after the
    // same pass (a section's render comes back short on all of them alike).
    std::atomic<bool> agreed_stop_{false};
    // Constant light: a section's last frame (without ambient, this rank's pixels), kept from the
    // end of its render until the next section, if carried, starts from it (SectionLayout::carried).
    std::vector<float> carry_;
    FrameBufferPool frame_buffers_;  // outlives the graph whose stages pass them round
    int next_frame_ = 0;             // the write stage's: the frame it must get next
};

}  // namespace sl
