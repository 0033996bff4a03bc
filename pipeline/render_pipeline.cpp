#include "pipeline/render_pipeline.h"

#include <tbb/flow_graph.h>

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "foundation/errors.h"
#include "pipeline/distributed/image_gather.h"
#include "pipeline/distributed/section_state_on_ranks.h"
#include "pipeline/exposure.h"
#include "pipeline/exposure_preview.h"
#include "pipeline/frame_buffer_pool.h"
#include "pipeline/resume.h"
#include "stages/output/exr_frame_check.h"
#include "stages/output/exr_io.h"
#include "pipeline/resume_checkpoints.h"
#include "stages/render/frame_assembly.h"

namespace sl {
namespace {

namespace flow = tbb::flow;
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

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

// What an EXR of this section says about itself: the passes it got, and whether an interrupt
// cut the section short (then --resume renders it further instead of keeping it).
FrameOutputs::Metadata frame_metadata(const Section& s) {
    FrameOutputs::Metadata m{{kPassesKey, std::to_string(s.passes)}};
    if (s.partial) m[kInterruptedKey] = "1";
    return m;
}

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

PipelineStats run_pipeline(const PipelineJob& job, FrameSink& outputs, const ProgressFn& progress,
                           const std::atomic<bool>& cancel) {
    const RenderContext& ctx = *job.ctx;
    const MemoryPlan& plan = job.plan;
    PipelineStats stats;
    const int passes = job.passes > 0 ? job.passes : ctx.scene.render.passes;
    const int64_t photons_per_pass = job.photons_per_pass > 0 ? job.photons_per_pass : ctx.scene.render.photons_per_pass;
    const EmissionMode mode = ctx.scene.emission.mode;
    const std::vector<SectionLayout> layouts = plan_sections(ctx, plan, job.strategy);
    auto resumed = [&](int s) { return s < static_cast<int>(job.on_disk.size()) && job.on_disk[s]; };
    // With several ranks, every rank takes part in whatever rank 0's outputs need (the
    // exposure, the cube's planes), so rank 0 decides; the frames come to it, in order.
    RankExchange* ex = ctx.exchange;
    const bool root = !ex || ex->rank() == 0;
    bool exposure_pending = outputs.needs_exposure();
    bool wants_cube = outputs.wants_cube();
    if (ex) {
        exposure_pending = ex->broadcast(Channel::Frames, exposure_pending);
        wants_cube = ex->broadcast(Channel::Frames, wants_cube);
    }
    // An interrupt, as every rank sees it: with ranks, only once they agreed to stop after the
    // same pass (a section's render comes back short on all of them alike).
    std::atomic<bool> agreed_stop{false};
    auto stopped = [&] { return ex ? agreed_stop.load() : cancel.load(); };
    auto whole_image = [&](std::vector<float>& rgb) {
        if (ex) gather_image(*ex, ctx.pixels(), rgb);
    };

    auto start_of = [&](int s) { return s < static_cast<int>(job.starts.size()) ? job.starts[s] : SectionStart{}; };
    auto log = [&](const std::string& line) {
        if (!root) return;
        if (job.log) job.log(line);
        else std::fprintf(stderr, "%s\n", line.c_str());
    };
    stats.passes_per_section.assign(static_cast<size_t>(plan.sections), 0);

    // The exposure, before any frame is encoded. With one section the section itself provides it
    // (below); a finished render resumed from disk is measured on the very frames it wrote, and
    // more sections (or one finished in its checkpoint) on a preview, which is deterministic: a
    // resumed run exposes as the first did.
    int preview_passes = 0;
    if (exposure_pending && plan.sections == 1 && resumed(0)) {
        if (root) outputs.set_exposure_plan(exposure_from_disk(ctx, job.exposure_rule, *job.exr_files));
        exposure_pending = false;
    } else if (exposure_pending && (plan.sections > 1 || start_of(0).finished)) {
        auto t0 = Clock::now();
        // Stopped by an interrupt or, with --time-limit, after a sixteenth of the budget.
        // With ranks, rank 0's clock (the ranks agree on stopping after each pass).
        auto stop = [&](int done) { return cancel.load() || (job.budget && root && job.budget->preview_over(done)); };
        const ExposurePreview e = exposure_from_preview(ctx, job.exposure_rule, stop);
        preview_passes = e.passes;
        stats.counts.add(e.counts);
        if (root) outputs.set_exposure_plan(e.exposure);
        exposure_pending = false;
        stats.passes_run += preview_passes;
        malloc_trim(0);  // the preview's photon map and buffer: back to the system
        stats.exposure_pass = since(t0);
        if (preview_passes > 0 && mode == EmissionMode::Constant) {  // a full-path pass, at full resolution
            if (job.budget) job.budget->expect_later_pass(e.full_pass_seconds);
            if (job.full_pass_seconds) job.full_pass_seconds(e.full_pass_seconds, preview_passes);
        }
    }

    // Constant light: a section's last frame (without ambient, this rank's pixels), kept from the
    // end of its render until the next section, if carried, starts from it (SectionLayout::carried).
    std::vector<float> carry;
    // The carried frame for section `index`, when the section before it was not rendered in this
    // run but read back from --exr-dir: its last EXR frame is that frame, bit for bit (float
    // pixels, and carried sections have no ambient term). Rank 0 reads it; each rank gets its pixels.
    auto carry_from_disk = [&](int index) {
        const int frame = layouts[static_cast<size_t>(index - 1)].end_frame - 1;
        std::vector<float> whole;
        if (root)
            whole = read_verified_exr(job.exr_files->exr_frame_path(frame),
                                      resume_expectation(ctx.width, ctx.height, job.fingerprint, frame));
        if (ex) scatter_image(*ex, ctx.pixels(), whole, carry, Channel::Passes);
        else carry = std::move(whole);
    };

    FrameBufferPool frame_buffers;  // outlives the graph whose stages pass them round
    flow::graph g;
    int next_section = 0;
    flow::input_node<int> sections(g, [&](tbb::flow_control& fc) -> int {
        if (next_section >= plan.sections || stopped()) {
            fc.stop();
            return 0;
        }
        return next_section++;
    });
    flow::limiter_node<int> sections_alive(g, plan.overlap ? 2 : 1);
    flow::function_node<int, SectionPtr> render(g, flow::serial, [&](int index) {
        auto s = std::make_shared<Section>();
        s->layout = layouts[index];
        s->last = index == plan.sections - 1;
        if (resumed(index)) {
            s->from_disk = true;
            ++stats.sections_resumed;
            s->passes = passes;
            stats.passes_per_section[index] = passes;
            return s;
        }
        if (stopped()) {  // taken from the queue just before the interrupt: not started
            s->complete = false;
            return s;
        }
        const SectionStart start = start_of(index);
        std::unique_ptr<SectionBuffer> buffer;
        if (start.from_checkpoint) {
            buffer = ex ? load_section_state_on_ranks(*ex, start.path, job.checkpointer->id_for(index), s->layout,
                                                      ctx.has_ambient(), ctx.pixels())
                        : load_section_state(start.path, job.checkpointer->id_for(index), s->layout, ctx.has_ambient());
            ++stats.sections_resumed;
        } else {
            const auto t0 = Clock::now();
            buffer = ex ? std::make_unique<SectionBuffer>(PixelShare{ex->rank(), ex->ranks(), ctx.pixels()}, s->layout,
                                                          ctx.initial_radius, ctx.has_ambient())
                        : std::make_unique<SectionBuffer>(ctx.pixels(), s->layout, ctx.initial_radius, ctx.has_ambient());
            stats.buffers += since(t0);
            if (s->layout.carried) {
                if (carry.empty()) carry_from_disk(index);
                set_carried(*buffer, carry);
            }
        }
        carry.clear();  // (a checkpoint holds its carried frame in the buffer)
        carry.shrink_to_fit();
        SectionBuffer* live = buffer.get();
        log(section_line(ctx, s->layout, plan.sections, start));
        bool by_interrupt = false;
        if (start.finished) {
            s->run.buffer = std::move(buffer);
        } else {
            if (job.budget) job.budget->section_started(live->passes_done);
            if (job.section_started) job.section_started(index, live->passes_done);
            auto on_pass = [&](int pass) {
                if (progress) progress(index, pass);
                if (job.budget) job.budget->pass_done(pass);
                if (job.checkpointer) job.checkpointer->after_pass(*live);
                if (job.preview) job.preview->after_pass(*live, outputs.exposure());
            };
            auto stop = [&] {
                if (cancel.load()) return by_interrupt = true;
                // With ranks, rank 0's budget decides (the ranks agree on stopping after each pass).
                return job.budget != nullptr && root && job.budget->stop_before_pass(live->passes_done);
            };
            s->run = render_section(ctx, s->layout, passes, photons_per_pass, on_pass, stop, std::move(buffer), &cancel);
        }
        s->passes = s->run.buffer->passes_done;
        // (a pass abandoned while its photons were traced ends the section without asking `stop`)
        if (!start.finished && cancel.load() && s->passes < passes) by_interrupt = true;
        // With ranks: an interrupt seen by any rank is one for all (they stopped after the same pass).
        if (ex) by_interrupt = ex->max(Channel::Passes, by_interrupt ? 1 : 0) != 0;
        if (by_interrupt) {
            // Every pass is a picture: the frames are written from the passes done, and the
            // state is saved so that --resume continues from here.
            s->partial = true;
            s->complete = s->passes > 0;
            if (job.checkpointer && s->passes > 0) stats.interrupted_checkpoint = job.checkpointer->save(*s->run.buffer, false);
            if (s->complete) stats.interrupted_section = index;
        } else {
            if (job.budget && !start.finished) {
                bool first_decision = !job.budget->passes();
                job.budget->section_finished(s->passes, false);
                if (first_decision && job.budget->passes() && job.passes_fixed) job.passes_fixed(*job.budget->passes());
            }
            // Without --exr-dir a finished section's frames exist nowhere else until the video
            // is closed: keep its final state so that --resume can write them again.
            if (job.checkpointer && job.checkpointer->settings().keep_finished && !s->last && !start.finished)
                job.checkpointer->save(*s->run.buffer, true);
        }
        if (s->complete) stats.passes_per_section[index] = s->passes;
        if (!by_interrupt && index + 1 < plan.sections && layouts[index + 1].carried && !resumed(index + 1))
            carried_frame(*s->run.buffer, carry);
        if (by_interrupt) agreed_stop = true;  // with ranks: they all stopped after the same pass
        if (!start.finished) stats.passes_run += s->passes - start.passes_done;
        if (job.preview && s->complete && !start.finished) job.preview->write(*s->run.buffer, outputs.exposure());
        stats.render.camera_paths += s->run.times.camera_paths;
        stats.render.photons += s->run.times.photons;
        stats.render.gather += s->run.times.gather;
        stats.render.grid += s->run.times.grid;
        stats.render.volume += s->run.times.volume;
        stats.render.volume_cpu += s->run.times.volume_cpu;
        stats.counts.add(s->run.counts);
        stats.photon_map_bytes = std::max(stats.photon_map_bytes, s->run.photon_map_bytes);
        if (s->complete) outputs.section_rendered(index, *s->run.buffer);
        else s->run.buffer.reset();
        return s;
    });
    // A serial node may start its next body before it hands on its last output (oneTBB spawns
    // the queued input first), so a section that returns at once (resumed, or stopped) could
    // overtake the one before it: sections are put back in index order before they are split.
    flow::sequencer_node<SectionPtr> sections_in_order(g, [](const SectionPtr& s) { return static_cast<size_t>(s->layout.index); });
    using Split = flow::multifunction_node<SectionPtr, std::tuple<FrameJob>>;
    Split split(g, flow::serial, [&](const SectionPtr& s, Split::output_ports_type& out) {
        if (!s->complete) return;  // never started: nothing to write
        for (int f = s->layout.first_frame; f < s->layout.end_frame; ++f) std::get<0>(out).try_put(FrameJob{s, f});
    });
    flow::queue_node<FrameJob> frame_queue(g);
    flow::limiter_node<FrameJob> frames_alive(g, 2);
    flow::function_node<FrameJob, FramePtr> assemble(g, flow::serial, [&](const FrameJob& job_in) {
        auto t0 = Clock::now();
        Section& s = *job_in.section;
        auto out = std::make_shared<FrameImage>(FrameImage{job_in.section, job_in.frame, {}, {}, {}, {}, {}, {}});
        FrameImage& img = *out;
        if (s.from_disk) {
            // Checked again as it is read: the file may have changed since --resume judged it.
            // With ranks, only rank 0 (which judged it) reads it: the image is whole there.
            if (root)
                img.rgb = read_verified_exr(job.exr_files->exr_frame_path(job_in.frame),
                                            resume_expectation(ctx.width, ctx.height, job.fingerprint, job_in.frame));
        } else {
            if (!s.assembler) {
                s.assembler.emplace(*s.run.buffer, mode, ctx.timeline.pulse_buckets);
                if (s.last) {
                    std::vector<float> steady;
                    s.assembler->steady(steady);
                    whole_image(steady);
                    // (a camera ray per pixel: only when the exposure or the black check needs it)
                    const std::vector<uint8_t> lamps =
                        exposure_pending || job.check_black ? emitter_pixels(ctx) : std::vector<uint8_t>();
                    // Decided here, handed to the outputs only by the write stage; nothing else
                    // sets it meanwhile: with several sections the preview fixed it before.
                    if (exposure_pending) {  // one section: it holds every frame
                        ExposureMeter meter(mode, job.exposure_rule, lamps);
                        measure_buffer(*s.run.buffer, ctx, meter, &steady);
                        if (root) img.exposure = meter.decide();
                        exposure_pending = false;
                    }
                    if (root && job.check_black) {
                        ExposureMeter light(EmissionMode::Constant, {}, lamps);
                        light.add_steady(steady.data(), ctx.pixels());
                        stats.steady_black = light.decide().black;
                    }
                    if (root) img.steady = std::move(steady);
                }
            }
            img.rgb = frame_buffers.take();
            s.assembler->frame(job_in.frame, img.rgb);
            whole_image(img.rgb);
            if (wants_cube) {
                if (job_in.frame == 0) {
                    s.assembler->before_plane(img.before);
                    whole_image(img.before);
                }
                img.bucket = frame_buffers.take();
                s.assembler->bucket_plane(job_in.frame, img.bucket);
                whole_image(img.bucket);
                if (s.last && job_in.frame + 1 == s.layout.end_frame) {
                    s.assembler->after_plane(img.after);
                    whole_image(img.after);
                }
            }
        }
        stats.assembly += since(t0);
        if (job.frame_assembled) job.frame_assembled(job_in.frame);
        return out;
    });
    // The same hazard between assembly and the writers: frames are put back in index order (the
    // exposure rides on the first one, and the video, y4m and cube are streams).
    flow::sequencer_node<FramePtr> frames_in_order(g, [](const FramePtr& f) { return static_cast<size_t>(f->frame); });
    int next_frame = 0;
    using Write = flow::multifunction_node<FramePtr, std::tuple<flow::continue_msg, flow::continue_msg>>;
    Write write(g, flow::serial, [&](const FramePtr& frame, Write::output_ports_type& out) {
        const FrameImage& img = *frame;
        // The sequencer makes this impossible; were it ever broken, no stream gets a frame out of order.
        if (img.frame != next_frame)
            throw RuntimeFailure("internal error: frame " + std::to_string(img.frame) + " reached the writers before frame " +
                        std::to_string(next_frame));
        ++next_frame;
        auto t0 = Clock::now();
        if (root) {
            if (img.exposure) outputs.set_exposure_plan(*img.exposure);
            if (!img.steady.empty()) outputs.write_steady(img.steady, frame_metadata(*img.section));
            outputs.write_frame(img.frame, img.rgb, img.section->from_disk, frame_metadata(*img.section));
        }
        if (!img.before.empty()) outputs.write_cube_plane(img.before);
        if (!img.bucket.empty()) outputs.write_cube_plane(img.bucket);
        if (!img.after.empty()) outputs.write_cube_plane(img.after);
        stats.writing += since(t0);
        frame_buffers.give(std::move(frame->rgb));
        frame_buffers.give(std::move(frame->bucket));
        bool last = img.frame + 1 == img.section->layout.end_frame;
        if (last) {  // free the section's buckets before another section may allocate its own
            if (!img.section->partial) ++stats.sections_done;
            // Its frames are in --exr-dir now: they, not the checkpoint, are what --resume reads.
            if (job.checkpointer && !img.section->partial && job.exr_files && !job.exr_files->exr_dir().empty())
                job.checkpointer->remove(img.section->layout.index);
            img.section->assembler.reset();
            img.section->run.buffer.reset();
            malloc_trim(0);  // hand the section's freed working memory back before the next one grows
            outputs.section_written(img.section->layout.index);
        }
        std::get<0>(out).try_put(flow::continue_msg());
        if (last) std::get<1>(out).try_put(flow::continue_msg());
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
