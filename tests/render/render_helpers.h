#pragma once
// Runs one whole-timeline convergence in-process (the program's own render, its frames kept in
// memory) and returns its frames and steady image.
#include <cmath>
#include <functional>
#include <vector>

#include "core/import/resolve_imports.h"
#include "pipeline/frames_in_memory.h"
#include "pipeline/render_frames.h"
#include "stages/render/render_context.h"

namespace sl::test {

struct Rendered {
    std::vector<std::vector<float>> frames;
    std::vector<float> steady;
    int width = 0, height = 0;
};

inline Rendered render_all(const SceneDesc& scene, int sections = 1) {
    RenderContext ctx(with_imports(scene));  // imported files read first, as the program does
    Rendered out;
    out.width = ctx.width;
    out.height = ctx.height;
    FramesInMemory sink;
    render_frames(ctx, {Strategy::Single, sections}, sink);
    out.frames = std::move(sink.frames);
    out.steady = std::move(sink.steady);
    return out;
}

// The same, with `set` turning the render context's internal switches first (tests that compare
// an estimator with the one before it).
inline Rendered render_switched(const SceneDesc& scene, const std::function<void(RenderContext&)>& set) {
    RenderContext ctx(with_imports(scene));
    set(ctx);
    Rendered out;
    out.width = ctx.width;
    out.height = ctx.height;
    FramesInMemory sink;
    render_frames(ctx, {Strategy::Single, 1}, sink);
    out.frames = std::move(sink.frames);
    out.steady = std::move(sink.steady);
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
