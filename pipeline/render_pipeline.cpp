#include "pipeline/render_pipeline.h"

#include <tbb/flow_graph.h>

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "stages/output/exr_io.h"
#include "stages/output/tone_map.h"
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
};
// Frames travel by pointer: a flow-graph edge copies its message, and a frame is megabytes.
using FramePtr = std::shared_ptr<FrameImage>;

// Pulse frames are far dimmer than the steady image, and a seen emitter lights only the first
// one: expose for the 99th percentile of the lit pixels of all frames pooled (a strided subset
// of pixels, at most about a million values).
double exposure_of_brightest_pulse_frame(const SectionBuffer& buffer, const RenderContext& ctx) {
    FrameAssembler pulse(buffer, EmissionMode::Pulse, ctx.pulse_buckets);
    const size_t pixels = ctx.pixels(), frames = static_cast<size_t>(buffer.layout.frames());
    const size_t stride = std::max<size_t>(1, pixels * frames / (1u << 20));
    std::vector<float> rgb, lit;
    for (int f = buffer.layout.first_frame; f < buffer.layout.end_frame; ++f) {
        pulse.frame(f, rgb);
        for (size_t p = (f * 7919u) % stride; p < pixels; p += stride) {
            float y = 0.2126f * rgb[3 * p] + 0.7152f * rgb[3 * p + 1] + 0.0722f * rgb[3 * p + 2];
            if (y > 0 && std::isfinite(y)) lit.push_back(y);
        }
    }
    if (lit.empty()) return 1.0;
    auto nth = lit.begin() + static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(lit.size() - 1));
    std::nth_element(lit.begin(), nth, lit.end());
    return 1.0 / *nth;
}

// A short convergence made only to choose the exposure before the first section's frames are
// encoded (with one section, the section itself provides it): the steady image for constant
// emission; for pulses, every frame at a quarter of the resolution (a sixteenth of the memory).
double exposure_from_preview(const RenderContext& ctx, SectionCounters& counters, const std::function<bool(int)>& stop,
                             int& passes_done) {
    const int passes = std::max(2, ctx.scene.render.passes / 8);
    int done = 0;
    auto on_pass = [&](int p) { done = passes_done = p; };
    auto cancelled = [&] { return stop(done); };
    const int64_t photons = ctx.scene.render.photons_per_pass;
    if (ctx.scene.emission.mode == EmissionMode::Pulse) {
        SceneDesc small = ctx.scene;
        small.camera.width = std::max(8, ctx.width / 4);
        small.camera.height = std::max(8, ctx.height / 4);
        small.render.radius = ctx.initial_radius;
        RenderContext preview(small);
        SectionLayout l = make_section(preview.timeline, EmissionMode::Pulse, preview.pulse_buckets, 1, 0);
        SectionRun run = render_section(preview, l, passes, photons, counters, on_pass, cancelled);
        return exposure_of_brightest_pulse_frame(*run.buffer, preview);
    }
    SectionLayout l;
    l.first_frame = l.end_frame = ctx.timeline.frames;
    l.first_bucket = l.end_frame;
    l.full_paths = true;
    SectionRun run = render_section(ctx, l, passes, photons, counters, on_pass, cancelled);
    FrameAssembler a(*run.buffer, EmissionMode::Constant, 1);
    std::vector<float> rgb;
    a.steady(rgb);
    return exposure_from_steady(rgb.data(), ctx.width, ctx.height);
}

// What an EXR of this section says about itself: the passes it got, and whether an interrupt
// cut the section short (then --resume renders it further instead of keeping it).
FrameOutputs::Metadata frame_metadata(const Section& s) {
    FrameOutputs::Metadata m{{kPassesKey, std::to_string(s.passes)}};
    if (s.partial) m[kInterruptedKey] = "1";
    return m;
}

}  // namespace

std::vector<SectionLayout> plan_sections(const RenderContext& ctx, const MemoryPlan& plan, Strategy strategy) {
    std::vector<SectionLayout> out;
    for (SectionLayout l : make_sections(ctx.timeline, ctx.scene.emission.mode, ctx.pulse_buckets, plan.sections)) {
        // The baseline renders every frame as a full, independent convergence, as the paper does.
        if (strategy == Strategy::FrameByFrame) l.full_paths = true;
        out.push_back(l);
    }
    return out;
}

PipelineStats run_pipeline(const PipelineJob& job, FrameOutputs& outputs, const ProgressFn& progress,
                           const std::atomic<bool>& cancel) {
    const RenderContext& ctx = *job.ctx;
    const MemoryPlan& plan = job.plan;
    PipelineStats stats;
    SectionCounters counters;
    const int passes = ctx.scene.render.passes;
    const int64_t photons_per_pass = ctx.scene.render.photons_per_pass;
    const EmissionMode mode = ctx.scene.emission.mode;
    const std::vector<SectionLayout> layouts = plan_sections(ctx, plan, job.strategy);
    auto resumed = [&](int s) { return s < static_cast<int>(job.on_disk.size()) && job.on_disk[s]; };
    auto start_of = [&](int s) { return s < static_cast<int>(job.starts.size()) ? job.starts[s] : SectionStart{}; };
    auto log = [&](const std::string& line) {
        if (job.log) job.log(line);
        else std::fprintf(stderr, "%s\n", line.c_str());
    };
    stats.passes_per_section.assign(static_cast<size_t>(plan.sections), 0);

    if (outputs.needs_exposure() && resumed(plan.sections - 1) && mode == EmissionMode::Constant) {
        ExrImage steady = read_exr(outputs.exr_steady_path());
        outputs.set_exposure(exposure_from_steady(steady.rgb.data(), ctx.width, ctx.height));
    } else if (outputs.needs_exposure() && (plan.sections > 1 || resumed(0) || start_of(0).finished)) {
        auto t0 = Clock::now();
        int preview_passes = 0;
        // Stopped by an interrupt or, with --time-limit, after a sixteenth of the budget.
        auto stop = [&](int done) { return cancel.load() || (job.budget && job.budget->preview_over(done)); };
        outputs.set_exposure(exposure_from_preview(ctx, counters, stop, preview_passes));
        malloc_trim(0);  // the preview's photon map and buffer: back to the system
        stats.exposure_pass = since(t0);
        if (preview_passes > 0 && mode == EmissionMode::Constant) {  // a full-resolution, full-path pass
            if (job.budget) job.budget->expect_later_pass(stats.exposure_pass / preview_passes);
            if (job.full_pass_seconds) job.full_pass_seconds(stats.exposure_pass / preview_passes, preview_passes);
        }
    }

    flow::graph g;
    int next_section = 0;
    flow::input_node<int> sections(g, [&](tbb::flow_control& fc) -> int {
        if (next_section >= plan.sections || cancel.load()) {
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
        if (cancel.load()) {  // taken from the queue just before the interrupt: not started
            s->complete = false;
            return s;
        }
        const SectionStart start = start_of(index);
        std::unique_ptr<SectionBuffer> buffer;
        if (start.from_checkpoint) {
            buffer = load_section_state(start.path, job.checkpointer->id_for(index), s->layout, ctx.has_ambient());
            ++stats.sections_resumed;
        } else {
            buffer = std::make_unique<SectionBuffer>(ctx.pixels(), s->layout, ctx.initial_radius, ctx.has_ambient());
        }
        SectionBuffer* live = buffer.get();
        char line[256];
        std::snprintf(line, sizeof line, "slowlight: section %d/%d, frames %d-%d: %s of time buckets%s", index + 1,
                      plan.sections, s->layout.first_frame, s->layout.end_frame - 1,
                      format_bytes(SectionBuffer::bytes_needed(ctx.pixels(), s->layout.slots(), ctx.has_ambient())).c_str(),
                      start.from_checkpoint ? (start.finished ? "; finished, from its checkpoint"
                                                              : ("; from its checkpoint at pass " +
                                                                 std::to_string(start.passes_done)).c_str())
                                            : "");
        log(line);
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
                return job.budget != nullptr && job.budget->stop_before_pass(live->passes_done);
            };
            s->run = render_section(ctx, s->layout, passes, photons_per_pass, counters, on_pass, stop, std::move(buffer),
                                    &cancel);
        }
        s->passes = s->run.buffer->passes_done;
        // (a pass abandoned while its photons were traced ends the section without asking `stop`)
        if (!start.finished && cancel.load() && s->passes < passes) by_interrupt = true;
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
        if (job.preview && s->complete && !start.finished) job.preview->write(*s->run.buffer, outputs.exposure());
        stats.render.camera += s->run.times.camera;
        stats.render.photons += s->run.times.photons;
        stats.render.gather += s->run.times.gather;
        stats.photon_map_bytes = std::max(stats.photon_map_bytes, s->run.photon_map_bytes);
        if (!s->complete) s->run.buffer.reset();
        return s;
    });
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
        auto out = std::make_shared<FrameImage>(FrameImage{job_in.section, job_in.frame, {}, {}, {}, {}});
        FrameImage& img = *out;
        if (s.from_disk) {
            img.rgb = read_exr(outputs.exr_frame_path(job_in.frame)).rgb;
        } else {
            if (!s.assembler) {
                s.assembler.emplace(*s.run.buffer, mode, ctx.pulse_buckets);
                if (s.last) {
                    std::vector<float> steady;
                    s.assembler->steady(steady);
                    if (outputs.needs_exposure())
                        outputs.set_exposure(mode == EmissionMode::Pulse
                                                 ? exposure_of_brightest_pulse_frame(*s.run.buffer, ctx)
                                                 : exposure_from_steady(steady.data(), ctx.width, ctx.height));
                    outputs.write_steady(steady, frame_metadata(s));
                }
            }
            s.assembler->frame(job_in.frame, img.rgb);
            if (outputs.wants_cube()) {
                if (job_in.frame == 0) s.assembler->before_plane(img.before);
                s.assembler->bucket_plane(job_in.frame, img.bucket);
                if (s.last && job_in.frame + 1 == s.layout.end_frame) s.assembler->after_plane(img.after);
            }
        }
        stats.assembly += since(t0);
        return out;
    });
    using Write = flow::multifunction_node<FramePtr, std::tuple<flow::continue_msg, flow::continue_msg>>;
    Write write(g, flow::serial, [&](const FramePtr& frame, Write::output_ports_type& out) {
        const FrameImage& img = *frame;
        auto t0 = Clock::now();
        outputs.write_frame(img.frame, img.rgb, img.section->from_disk, frame_metadata(*img.section));
        if (!img.before.empty()) outputs.write_cube_plane(img.before);
        if (!img.bucket.empty()) outputs.write_cube_plane(img.bucket);
        if (!img.after.empty()) outputs.write_cube_plane(img.after);
        stats.writing += since(t0);
        bool last = img.frame + 1 == img.section->layout.end_frame;
        if (last) {  // free the section's buckets before another section may allocate its own
            if (!img.section->partial) ++stats.sections_done;
            // Its frames are in --exr-dir now: they, not the checkpoint, are what --resume reads.
            if (job.checkpointer && !img.section->partial && !outputs.exr_dir().empty())
                job.checkpointer->remove(img.section->layout.index);
            img.section->assembler.reset();
            img.section->run.buffer.reset();
            malloc_trim(0);  // hand the section's freed working memory back before the next one grows
        }
        std::get<0>(out).try_put(flow::continue_msg());
        if (last) std::get<1>(out).try_put(flow::continue_msg());
    });

    flow::make_edge(sections, sections_alive);
    flow::make_edge(sections_alive, render);
    flow::make_edge(render, split);
    flow::make_edge(std::get<0>(split.output_ports()), frame_queue);
    flow::make_edge(frame_queue, frames_alive);
    flow::make_edge(frames_alive, assemble);
    flow::make_edge(assemble, write);
    flow::make_edge(flow::output_port<0>(write), frames_alive.decrementer());
    flow::make_edge(flow::output_port<1>(write), sections_alive.decrementer());
    sections.activate();
    g.wait_for_all();

    stats.photons = counters.photons.photons.load();
    stats.photon_records = counters.photons.stored.load();
    stats.rays = counters.photons.rays.load() + counters.camera.rays.load();
    stats.interrupted = cancel.load();
    return stats;
}

}  // namespace sl
