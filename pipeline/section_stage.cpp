// The render stage: one section from its start (fresh, carried from the section before, or a
// checkpoint) through its passes to the state its frames are assembled from, with what an
// interrupt or a time budget decides on the way.
#include <cstdio>

#include "pipeline/distributed/image_gather.h"
#include "pipeline/distributed/section_state_on_ranks.h"
#include "pipeline/pipeline_run.h"
#include "pipeline/resume.h"
#include "stages/output/exr_frame_check.h"

namespace sl {
namespace {

// "slowlight: section 2/4, frames 12-23: 96 MiB of time buckets; from its checkpoint at pass 8"
std::string section_line(const RenderContext& ctx, const SectionLayout& layout, int sections, const SectionStart& start) {
    const RankExchange* ex = ctx.exchange;
    char line[256];
    std::snprintf(line, sizeof line, "slowlight: section %d/%d, frames %d-%d: %s of time buckets%s%s", layout.index + 1,
                  sections, layout.first_frame, layout.end_frame - 1,
                  format_bytes(SectionBuffer::bytes_needed(ex ? PixelShare{0, ex->ranks(), ctx.pixels()}.count()
                                                              : ctx.pixels(),
                                                           layout.slots(), ctx.has_ambient()))
                      .c_str(),
                  ex ? " per rank" : "",
                  start.from_checkpoint ? (start.finished ? "; finished, from its checkpoint"
                                                          : ("; from its checkpoint at pass " +
                                                             std::to_string(start.passes_done)).c_str())
                                        : "");
    return line;
}

}  // namespace

SectionPtr PipelineRun::render_section(int index) {
    auto s = std::make_shared<Section>();
    s->layout = layouts_[static_cast<size_t>(index)];
    s->last = index == plan_.sections - 1;
    if (resumed(index)) {  // its frames are on disk: read back by the assembly
        s->from_disk = true;
        ++stats_.sections_resumed;
        s->passes = passes_;
        stats_.passes_per_section[static_cast<size_t>(index)] = passes_;
        return s;
    }
    if (stopped()) {  // taken from the queue just before the interrupt: not started
        s->complete = false;
        return s;
    }
    const SectionStart start = start_of(index);
    std::unique_ptr<SectionBuffer> buffer = section_buffer(*s, start);
    log(section_line(ctx_, s->layout, plan_.sections, start));
    const bool by_interrupt = run_passes(*s, start, std::move(buffer));
    settle_section(*s, start, by_interrupt);
    count_section(*s, start);
    if (s->complete) outputs_.section_rendered(index, *s->run.buffer);
    else s->run.buffer.reset();
    return s;
}

// The section's time buckets: from its checkpoint, or new (and, when carried, starting from the
// last frame of the section before).
std::unique_ptr<SectionBuffer> PipelineRun::section_buffer(Section& s, const SectionStart& start) {
    std::unique_ptr<SectionBuffer> buffer;
    const int index = s.layout.index;
    if (start.from_checkpoint) {
        buffer = ex_ ? load_section_state_on_ranks(*ex_, start.path, job_.checkpointer->id_for(index), s.layout,
                                                   ctx_.has_ambient(), ctx_.pixels())
                     : load_section_state(start.path, job_.checkpointer->id_for(index), s.layout, ctx_.has_ambient());
        ++stats_.sections_resumed;
    } else {
        const auto t0 = Clock::now();
        buffer = new_section_buffer(ctx_, s.layout);
        stats_.buffers += since(t0);
        if (s.layout.carried) {
            if (carry_.empty()) carry_from_disk(index);
            set_carried(*buffer, carry_);
        }
    }
    carry_.clear();  // (a checkpoint holds its carried frame in the buffer)
    carry_.shrink_to_fit();
    return buffer;
}

// The carried frame for section `index`, when the section before it was not rendered in this
// run but read back from --exr-dir: its last EXR frame is that frame, bit for bit (float
// pixels, and carried sections have no ambient term). Rank 0 reads it; each rank gets its pixels.
void PipelineRun::carry_from_disk(int index) {
    const int frame = layouts_[static_cast<size_t>(index - 1)].end_frame - 1;
    std::vector<float> whole;
    if (root_)
        whole = read_verified_exr(job_.exr_files->exr_frame_path(frame),
                                  resume_expectation(ctx_.width, ctx_.height, job_.fingerprint, frame));
    if (ex_) scatter_image(*ex_, ctx_.pixels(), whole, carry_, Channel::Passes);
    else carry_ = std::move(whole);
}

// The passes (none for a section finished in its checkpoint). True: an interrupt cut them short
// (with ranks: any rank's, as they all stopped after the same pass).
bool PipelineRun::run_passes(Section& s, const SectionStart& start, std::unique_ptr<SectionBuffer> buffer) {
    const int index = s.layout.index;
    bool by_interrupt = false;
    if (start.finished) {
        s.run.buffer = std::move(buffer);
    } else {
        SectionBuffer* live = buffer.get();
        if (job_.budget) job_.budget->section_started(live->passes_done);
        if (job_.section_started) job_.section_started(index, live->passes_done);
        auto on_pass = [&](int pass) {
            if (progress_) progress_(index, pass);
            if (job_.budget) job_.budget->pass_done(pass);
            if (job_.checkpointer) job_.checkpointer->after_pass(*live);
            if (job_.preview) job_.preview->after_pass(*live, outputs_.exposure());
        };
        auto stop = [&] {
            if (cancel_.load()) return by_interrupt = true;
            // With ranks, rank 0's budget decides (the ranks agree on stopping after each pass).
            return job_.budget != nullptr && root_ && job_.budget->stop_before_pass(live->passes_done);
        };
        s.run = sl::render_section(ctx_, s.layout, passes_, photons_per_pass_, on_pass, stop, std::move(buffer), &cancel_);
    }
    s.passes = s.run.buffer->passes_done;
    // (a pass abandoned while its photons were traced ends the section without asking `stop`)
    if (!start.finished && cancel_.load() && s.passes < passes_) by_interrupt = true;
    if (ex_) by_interrupt = ex_->max(Channel::Passes, by_interrupt ? 1 : 0) != 0;
    return by_interrupt;
}

// What the end of the passes means: interrupted, every pass is still a picture (written from the
// passes done, the state saved for --resume); finished, the time budget learns from it and the
// state is kept where --resume would otherwise have nothing.
void PipelineRun::settle_section(Section& s, const SectionStart& start, bool by_interrupt) {
    const int index = s.layout.index;
    if (by_interrupt) {
        s.partial = true;
        s.complete = s.passes > 0;
        if (job_.checkpointer && s.passes > 0) stats_.interrupted_checkpoint = job_.checkpointer->save(*s.run.buffer, false);
        if (s.complete) stats_.interrupted_section = index;
        agreed_stop_ = true;  // with ranks: they all stopped after the same pass
        return;
    }
    if (job_.budget && !start.finished) {
        const bool first_decision = !job_.budget->passes();
        job_.budget->section_finished(s.passes, false);
        if (first_decision && job_.budget->passes() && job_.passes_fixed) job_.passes_fixed(*job_.budget->passes());
    }
    // Without --exr-dir a finished section's frames exist nowhere else until the video is
    // closed: keep its final state so that --resume can write them again.
    if (job_.checkpointer && job_.checkpointer->settings().keep_finished && !s.last && !start.finished)
        job_.checkpointer->save(*s.run.buffer, true);
    if (index + 1 < plan_.sections && layouts_[static_cast<size_t>(index) + 1].carried && !resumed(index + 1))
        carried_frame(*s.run.buffer, carry_);
}

void PipelineRun::count_section(const Section& s, const SectionStart& start) {
    if (s.complete) stats_.passes_per_section[static_cast<size_t>(s.layout.index)] = s.passes;
    if (!start.finished) stats_.passes_run += s.passes - start.passes_done;
    if (job_.preview && s.complete && !start.finished) job_.preview->write(*s.run.buffer, outputs_.exposure());
    stats_.render.camera_paths += s.run.times.camera_paths;
    stats_.render.photons += s.run.times.photons;
    stats_.render.gather += s.run.times.gather;
    stats_.render.grid += s.run.times.grid;
    stats_.render.volume += s.run.times.volume;
    stats_.render.volume_cpu += s.run.times.volume_cpu;
    stats_.counts.add(s.run.counts);
    stats_.photon_map_bytes = std::max(stats_.photon_map_bytes, s.run.photon_map_bytes);
}

}  // namespace sl
