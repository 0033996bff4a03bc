#pragma once
// Runs one whole-timeline convergence in-process and returns its frames and steady image.
#include <vector>

#include "stages/render/frame_assembly.h"
#include "stages/render/render_context.h"
#include "stages/render/section_renderer.h"

namespace sl::test {

struct Rendered {
    std::vector<std::vector<float>> frames;
    std::vector<float> steady;
    int width = 0, height = 0;
};

inline Rendered render_all(const SceneDesc& scene, EmissionMode mode = EmissionMode::Constant, int sections = 1) {
    RenderContext ctx(scene);
    Rendered out;
    out.width = ctx.width;
    out.height = ctx.height;
    SectionCounters counters;
    for (int k = 0; k < sections; ++k) {
        SectionLayout layout = make_section(ctx.timeline, ctx.scene.emission.mode, ctx.pulse_buckets, sections, k);
        SectionRun run = render_section(ctx, layout, scene.render.passes, scene.render.photons_per_pass, counters);
        FrameAssembler a(*run.buffer, mode, ctx.pulse_buckets);
        for (int f = layout.first_frame; f < layout.end_frame; ++f) {
            out.frames.emplace_back();
            a.frame(f, out.frames.back());
        }
        if (k == sections - 1) a.steady(out.steady);
    }
    return out;
}

inline double rmse(const std::vector<float>& a, const std::vector<float>& b) {
    double s = 0;
    for (size_t i = 0; i < a.size(); ++i) s += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    return std::sqrt(s / static_cast<double>(a.size()));
}

inline double mean(const std::vector<float>& a) {
    double s = 0;
    for (float v : a) s += v;
    return s / static_cast<double>(a.size());
}

}  // namespace sl::test
