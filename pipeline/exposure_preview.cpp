#include "pipeline/exposure_preview.h"

#include <algorithm>

#include "pipeline/distributed/image_gather.h"
#include "stages/output/exr_io.h"
#include "stages/render/frame_assembly.h"

namespace sl {
namespace {

// Turns this rank's pixels of an image into the whole image on rank 0 (and an empty one on the
// other ranks); in one process the image already is whole.
void whole_image_of(const RenderContext& ctx, std::vector<float>& rgb) {
    if (ctx.exchange) gather_image(*ctx.exchange, ctx.pixels(), rgb);
}

// The preview's passes: an eighth of the render's, at least 4 (or all, if fewer).
int preview_passes(int passes) { return std::min(passes, std::max(4, passes / 8)); }

}  // namespace

void measure_buffer(const SectionBuffer& buffer, const RenderContext& ctx, ExposureMeter& meter,
                    const std::vector<float>* steady) {
    std::vector<float> rgb;
    if (steady) {
        if (!steady->empty()) meter.add_steady(steady->data(), ctx.pixels());
    } else if (buffer.layout.has_after) {  // the full-path section: its slots sum to the steady image
        FrameAssembler(buffer, EmissionMode::Pulse, 1).steady(rgb);  // (no running sum needed for it)
        whole_image_of(ctx, rgb);
        if (!rgb.empty()) meter.add_steady(rgb.data(), ctx.pixels());
    }
    if (!meter.wants_frames()) return;
    FrameAssembler a(buffer, ctx.emission, ctx.timeline.pulse_buckets);
    for (int f = buffer.layout.first_frame; f < buffer.layout.end_frame; ++f) {
        a.frame(f, rgb);
        whole_image_of(ctx, rgb);
        if (!rgb.empty()) meter.add_frame(f, rgb.data(), ctx.pixels());
    }
}

// A short convergence made only to choose the exposure before the first section's frames are
// encoded (with one section, the section itself provides it), at a quarter of the resolution
// (a sixteenth of the camera work): the steady image alone when that is all the rule needs,
// every frame for pulses and --exposure-follow. The statistic is a mean over pixels, so neither
// the resolution nor the preview's fewer passes move it.
ExposurePreview exposure_from_preview(const RenderContext& ctx, const ExposureRule& rule,
                                      const std::function<bool(int)>& stop) {
    ExposurePreview out;
    const int passes = preview_passes(ctx.render.passes);
    auto on_pass = [&](int p) { out.passes = p; };
    auto cancelled = [&] { return stop(out.passes); };
    const EmissionMode mode = ctx.emission;
    const bool steady_only = !(mode == EmissionMode::Pulse || rule.follow);
    // The steady image's mean is the light the whole room receives: a quarter of the photons
    // still puts four times as many on each preview pixel as the render does. Frames (pulses,
    // --exposure-follow) keep them all: the brightest of many noisy frame means is biased high.
    const int64_t photons = steady_only ? std::max<int64_t>(1, ctx.render.photons_per_pass / 4)
                                        : ctx.render.photons_per_pass;
    SceneDesc small = ctx.scene;
    // At least 64 pixels a side (or the image's own): a mean over fewer is too noisy.
    small.camera.width = std::max(std::min(64, ctx.width), ctx.width / 4);
    small.camera.height = std::max(std::min(64, ctx.height), ctx.height / 4);
    small.render.radius = ctx.initial_radius;
    RenderContext preview(small);
    preview.exchange = ctx.exchange;
    SectionLayout l;
    if (!steady_only) {
        l = make_section(preview.timeline, mode, 1, 0);
    } else {  // the steady image only: a "before" and an "after" slot, full paths
        l.first_frame = l.end_frame = preview.timeline.frames;
        l.first_bucket = l.end_frame;
        l.full_paths = true;
    }
    SectionRun run = render_section(preview, l, passes, photons, on_pass, cancelled);
    ExposureMeter meter(mode, rule, emitter_pixels(preview));
    measure_buffer(*run.buffer, preview, meter);
    out.exposure = meter.decide();
    out.counts = run.counts;
    // What a pass at full resolution would take: the photons times the ratio of photons, the
    // camera's part (paths, gathers, the beam estimate) times the ratio of pixels.
    if (out.passes > 0) {
        const double pixels = static_cast<double>(ctx.pixels()) / static_cast<double>(preview.pixels());
        const double more = static_cast<double>(ctx.render.photons_per_pass) / static_cast<double>(photons);
        const StageTimes& t = run.times;
        out.full_pass_seconds = (more * t.photons + pixels * (t.camera_paths + t.gather + t.volume)) / out.passes;
    }
    return out;
}

ExposurePlan exposure_from_disk(const RenderContext& ctx, const ExposureRule& rule, const FrameOutputs& outputs) {
    ExposureMeter meter(ctx.emission, rule, emitter_pixels(ctx));
    ExrImage steady = read_exr(outputs.exr_steady_path(), outputs.frame_size());
    meter.add_steady(steady.rgb.data(), ctx.pixels());
    if (meter.wants_frames())
        for (int f = 0; f < ctx.timeline.frames; ++f)
            meter.add_frame(f, read_exr(outputs.exr_frame_path(f), outputs.frame_size()).rgb.data(), ctx.pixels());
    return meter.decide();
}

}  // namespace sl
