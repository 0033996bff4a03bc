#include "pipeline/render_pipeline.h"

#include <tbb/flow_graph.h>

#include <malloc.h>

#include <cstdio>

#include "pipeline/distributed/image_gather.h"
#include "pipeline/exposure_preview.h"
#include "pipeline/pipeline_run.h"
#include "pipeline/resume.h"

namespace sl {

PipelineStats run_pipeline(const PipelineJob& job, FrameSink& outputs, const ProgressFn& progress,
                           const std::atomic<bool>& cancel) {
    PipelineRun run(job, outputs, progress, cancel);
    run.expose_before_frames();
    run.stream_sections();
    return run.totals();
}

PipelineRun::PipelineRun(const PipelineJob& job, FrameSink& outputs, const ProgressFn& progress,
                         const std::atomic<bool>& cancel)
    : job_(job),
      ctx_(*job.ctx),
      plan_(job.plan),
      outputs_(outputs),
      progress_(progress),
      cancel_(cancel),
      passes_(job.passes > 0 ? job.passes : ctx_.render.passes),
      photons_per_pass_(job.photons_per_pass > 0 ? job.photons_per_pass : ctx_.render.photons_per_pass),
      mode_(ctx_.emission),
      layouts_(plan_sections(ctx_, plan_, job.strategy)),
      ex_(ctx_.exchange),
      root_(!ex_ || ex_->rank() == 0),
      exposure_pending_(outputs.needs_exposure()),
      wants_cube_(outputs.wants_cube()) {
    if (ex_) {
        exposure_pending_ = ex_->broadcast(Channel::Frames, exposure_pending_);
        wants_cube_ = ex_->broadcast(Channel::Frames, wants_cube_);
    }
    stats_.passes_per_section.assign(static_cast<size_t>(plan_.sections), 0);
}

void PipelineRun::log(const std::string& line) const {
    if (!root_) return;
    if (job_.log) job_.log(line);
    else std::fprintf(stderr, "%s\n", line.c_str());
}

void PipelineRun::whole_image(std::vector<float>& rgb) const {
    if (ex_) gather_image(*ex_, ctx_.pixels(), rgb);
}

// The exposure, before any frame is encoded. With one section the section itself provides it
// (decide_from_steady); a finished render resumed from disk is measured on the very frames it
// wrote, and more sections (or one finished in its checkpoint) on a preview, which is
// deterministic: a resumed run exposes as the first did.
void PipelineRun::expose_before_frames() {
    if (exposure_pending_ && plan_.sections == 1 && resumed(0)) {
        if (root_) outputs_.set_exposure_plan(exposure_from_disk(ctx_, job_.exposure_rule, *job_.exr_files));
        exposure_pending_ = false;
        return;
    }
    if (!exposure_pending_ || (plan_.sections == 1 && !start_of(0).finished)) return;
    const auto t0 = Clock::now();
    // Stopped by an interrupt or, with --time-limit, after a sixteenth of the budget.
    // With ranks, rank 0's clock (the ranks agree on stopping after each pass).
    auto stop = [&](int done) { return cancel_.load() || (job_.budget && root_ && job_.budget->preview_over(done)); };
    const ExposurePreview e = exposure_from_preview(ctx_, job_.exposure_rule, stop);
    stats_.counts.add(e.counts);
    if (root_) outputs_.set_exposure_plan(e.exposure);
    exposure_pending_ = false;
    stats_.passes_run += e.passes;
    malloc_trim(0);  // the preview's photon map and buffer: back to the system
    stats_.exposure_pass = since(t0);
    if (e.passes > 0 && mode_ == EmissionMode::Constant) {  // a full-path pass, at full resolution
        if (job_.budget) job_.budget->expect_later_pass(e.full_pass_seconds);
        if (job_.full_pass_seconds) job_.full_pass_seconds(e.full_pass_seconds, e.passes);
    }
}

// sections -> limiter (1 or 2 alive) -> render -> in section order -> split into frames -> queue
// -> limiter (2 frames) -> assemble -> in frame order -> write; the write stage frees a frame's
// place, and a section's when its last frame is written.
void PipelineRun::stream_sections() {
    namespace flow = tbb::flow;
    flow::graph g;
    int next_section = 0;
    flow::input_node<int> sections(g, [&](tbb::flow_control& fc) -> int {
        if (next_section >= plan_.sections || stopped()) {
            fc.stop();
            return 0;
        }
        return next_section++;
    });
    flow::limiter_node<int> sections_alive(g, plan_.overlap ? 2 : 1);
    flow::function_node<int, SectionPtr> render(g, flow::serial, [&](int index) { return render_section(index); });
    // A serial node may start its next body before it hands on its last output (oneTBB spawns
    // the queued input first), so a section that returns at once (resumed, or stopped) could
    // overtake the one before it, and a frame the one before it: both are put back in order.
    flow::sequencer_node<SectionPtr> sections_in_order(g, [](const SectionPtr& s) { return static_cast<size_t>(s->layout.index); });
    using Split = flow::multifunction_node<SectionPtr, std::tuple<FrameJob>>;
    Split split(g, flow::serial, [&](const SectionPtr& s, Split::output_ports_type& out) {
        if (!s->complete) return;  // never started: nothing to write
        for (int f = s->layout.first_frame; f < s->layout.end_frame; ++f) std::get<0>(out).try_put(FrameJob{s, f});
    });
    flow::queue_node<FrameJob> frame_queue(g);
    flow::limiter_node<FrameJob> frames_alive(g, 2);
    flow::function_node<FrameJob, FramePtr> assemble(g, flow::serial, [&](const FrameJob& f) { return this->assemble(f); });
    flow::sequencer_node<FramePtr> frames_in_order(g, [](const FramePtr& f) { return static_cast<size_t>(f->frame); });
    using Write = flow::multifunction_node<FramePtr, std::tuple<flow::continue_msg, flow::continue_msg>>;
    Write write(g, flow::serial, [&](const FramePtr& frame, Write::output_ports_type& out) {
        const bool section_done = this->write(*frame);
        std::get<0>(out).try_put(flow::continue_msg());
        if (section_done) std::get<1>(out).try_put(flow::continue_msg());
    });

    flow::make_edge(sections, sections_alive);
    flow::make_edge(sections_alive, render);
    flow::make_edge(render, sections_in_order);
    flow::make_edge(sections_in_order, split);
    flow::make_edge(std::get<0>(split.output_ports()), frame_queue);
    flow::make_edge(frame_queue, frames_alive);
    flow::make_edge(frames_alive, assemble);
    flow::make_edge(assemble, frames_in_order);
    flow::make_edge(frames_in_order, write);
    flow::make_edge(flow::output_port<0>(write), frames_alive.decrementer());
    flow::make_edge(flow::output_port<1>(write), sections_alive.decrementer());
    sections.activate();
    g.wait_for_all();
}

// This rank's counters and, with ranks, the job's totals.
PipelineStats PipelineRun::totals() {
    PipelineStats& stats = stats_;
    RankExchange* ex = ex_;
    stats.photons = stats.counts.photons;
    stats.photon_records = stats.counts.stored;
    stats.rays = stats.counts.rays();
    stats.interrupted = stopped();
    if (ex) {  // every rank counted its own photons and rays: the job's totals
        uint64_t totals[4] = {stats.photons, stats.photon_records, stats.rays, stats.interrupted ? 1u : 0u};
        ex->sum(Channel::Passes, totals, 4);
        stats.photons = totals[0];
        stats.photon_records = totals[1];
        stats.rays = totals[2];
        stats.interrupted = totals[3] > 0;
        stats.ranks = ex->ranks();
        const int passes_ch = static_cast<int>(Channel::Passes), photons_ch = static_cast<int>(Channel::Photons),
                  frames_ch = static_cast<int>(Channel::Frames);
        stats.exchanged_sent[0] = ex->sent[passes_ch] + ex->sent[photons_ch];
        stats.exchanged_received[0] = ex->received[passes_ch] + ex->received[photons_ch];
        stats.exchanged_sent[1] = ex->sent[frames_ch];
        stats.exchanged_received[1] = ex->received[frames_ch];
        stats.photon_transfer_seconds = ex->transfer_seconds[photons_ch];
    }
    return stats;
}

}  // namespace sl
