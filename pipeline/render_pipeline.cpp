#include "pipeline/render_pipeline.h"

#include <tbb/flow_graph.h>

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "pipeline/resume.h"
#include "stages/output/exr_frame_check.h"
#include "stages/output/tone_map.h"
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
    bool complete = true;    // false when interrupted: its frames are never written
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
    std::optional<double> exposure;
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
double exposure_from_preview(const RenderContext& ctx, SectionCounters& counters) {
    const int passes = std::max(2, ctx.scene.render.passes / 8);
    const int64_t photons = ctx.scene.render.photons_per_pass;
    if (ctx.scene.emission.mode == EmissionMode::Pulse) {
        SceneDesc small = ctx.scene;
        small.camera.width = std::max(8, ctx.width / 4);
        small.camera.height = std::max(8, ctx.height / 4);
        small.render.radius = ctx.initial_radius;
        RenderContext preview(small);
        SectionLayout l = make_section(preview.timeline, EmissionMode::Pulse, preview.pulse_buckets, 1, 0);
        SectionRun run = render_section(preview, l, passes, photons, counters);
        return exposure_of_brightest_pulse_frame(*run.buffer, preview);
    }
    SectionLayout l;
    l.first_frame = l.end_frame = ctx.timeline.frames;
    l.first_bucket = l.end_frame;
    l.full_paths = true;
    SectionRun run = render_section(ctx, l, passes, photons, counters);
    FrameAssembler a(*run.buffer, EmissionMode::Constant, 1);
    std::vector<float> rgb;
    a.steady(rgb);
    return exposure_from_steady(rgb.data(), ctx.width, ctx.height);
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

    if (outputs.needs_exposure() && resumed(plan.sections - 1) && mode == EmissionMode::Constant) {
        std::vector<float> steady = read_verified_exr(
            outputs.exr_steady_path(), resume_expectation(ctx.width, ctx.height, job.fingerprint, std::nullopt));
        outputs.set_exposure(exposure_from_steady(steady.data(), ctx.width, ctx.height));
    } else if (outputs.needs_exposure() && (plan.sections > 1 || resumed(0))) {
        auto t0 = Clock::now();
        outputs.set_exposure(exposure_from_preview(ctx, counters));
        malloc_trim(0);  // the preview's photon map and buffer: back to the system
        stats.exposure_pass = since(t0);
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
            return s;
        }
        if (cancel.load()) {  // taken from the queue just before the interrupt: not started
            s->complete = false;
            return s;
        }
        std::fprintf(stderr, "slowlight: section %d/%d, frames %d-%d: %s of time buckets\n", index + 1,
                     plan.sections, s->layout.first_frame, s->layout.end_frame - 1,
                     format_bytes(SectionBuffer::bytes_needed(ctx.pixels(), s->layout.slots(), ctx.has_ambient())).c_str());
        s->run = render_section(ctx, s->layout, passes, photons_per_pass, counters,
                                [&](int pass) { if (progress) progress(index, pass); },
                                [&] { return cancel.load(); });
        s->complete = s->run.buffer->passes_done == passes;
        stats.render.camera += s->run.times.camera;
        stats.render.photons += s->run.times.photons;
        stats.render.gather += s->run.times.gather;
        stats.photon_map_bytes = std::max(stats.photon_map_bytes, s->run.photon_map_bytes);
        if (!s->complete) s->run.buffer.reset();
        return s;
    });
    using Split = flow::multifunction_node<SectionPtr, std::tuple<FrameJob>>;
    Split split(g, flow::serial, [&](const SectionPtr& s, Split::output_ports_type& out) {
        if (!s->complete) return;  // interrupted: a half-converged section is not written
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
            img.rgb = read_verified_exr(outputs.exr_frame_path(job_in.frame),
                                        resume_expectation(ctx.width, ctx.height, job.fingerprint, job_in.frame));
        } else {
            if (!s.assembler) {
                s.assembler.emplace(*s.run.buffer, mode, ctx.pulse_buckets);
                if (s.last) {
                    s.assembler->steady(img.steady);
                    // Read here, set only by the write stage; nothing else sets it meanwhile:
                    // with several sections the preview fixed it before the graph started.
                    if (outputs.needs_exposure())
                        img.exposure = mode == EmissionMode::Pulse
                                           ? exposure_of_brightest_pulse_frame(*s.run.buffer, ctx)
                                           : exposure_from_steady(img.steady.data(), ctx.width, ctx.height);
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
        if (img.exposure) outputs.set_exposure(*img.exposure);
        if (!img.steady.empty()) outputs.write_steady(img.steady);
        outputs.write_frame(img.frame, img.rgb, img.section->from_disk);
        if (!img.before.empty()) outputs.write_cube_plane(img.before);
        if (!img.bucket.empty()) outputs.write_cube_plane(img.bucket);
        if (!img.after.empty()) outputs.write_cube_plane(img.after);
        stats.writing += since(t0);
        bool last = img.frame + 1 == img.section->layout.end_frame;
        if (last) {  // free the section's buckets before another section may allocate its own
            ++stats.sections_done;
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
