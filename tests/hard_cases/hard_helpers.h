#pragma once
// Shared pieces of the hard-case tests: an in-process render that also inspects the raw
// section buffers (every accumulator slot, radius and photon count), NaN/Inf counting, and
// scenes built in code or as JSON text.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "core/import/resolve_imports.h"
#include "config/parse_scene.h"
#include "config/scene_desc.h"
#include "pipeline/frames_in_memory.h"
#include "pipeline/render_frames.h"
#include "stages/render/render_context.h"
#include "tests/common/temp_dir.h"
#include "tests/render/scenes_for_tests.h"

namespace sl::hard {

using Image = std::vector<float>;

template <class Values>
size_t count_non_finite(const Values& v) {
    size_t n = 0;
    for (auto x : v) n += !std::isfinite(x);
    return n;
}

struct Rendered {
    std::vector<Image> frames;
    Image steady;
    int width = 0, height = 0;
    // Raw state of every section, scanned before it was freed.
    size_t buffer_non_finite = 0;   // accumulators, ambient, radius^2, photon counts
    double min_radius2 = std::numeric_limits<double>::infinity(), max_radius2 = 0;
    double min_photon_count = std::numeric_limits<double>::infinity(), max_photon_count = 0;
    std::vector<double> radius2, photon_count;  // of the last section
    double initial_radius = 0;

    size_t image_non_finite() const {
        size_t n = count_non_finite(steady);
        for (const Image& f : frames) n += count_non_finite(f);
        return n;
    }
    const float* px(const Image& img, int x, int y) const { return &img[(static_cast<size_t>(y) * width + x) * 3]; }
};

// Renders every frame and the steady image with `sections` sections (frame_by_frame: one per
// frame, each with full paths, as `--strategy frame-by-frame`).
inline Rendered render(const SceneDesc& scene, int sections = 1, bool frame_by_frame = false) {
    RenderContext ctx(with_imports(scene));  // imported files read first, as the program does
    Rendered out;
    out.width = ctx.width;
    out.height = ctx.height;
    out.initial_radius = ctx.initial_radius;
    FramesInMemory sink;
    sink.on_section_rendered = [&](int, const SectionBuffer& b) {
        out.buffer_non_finite += count_non_finite(b.accum) + count_non_finite(b.ambient) +
                                 count_non_finite(b.radius2) + count_non_finite(b.photon_count);
        for (double r2 : b.radius2) {
            out.min_radius2 = std::min(out.min_radius2, r2);
            out.max_radius2 = std::max(out.max_radius2, r2);
        }
        for (double n : b.photon_count) {
            out.min_photon_count = std::min(out.min_photon_count, n);
            out.max_photon_count = std::max(out.max_photon_count, n);
        }
        out.radius2 = b.radius2;
        out.photon_count = b.photon_count;
    };
    render_frames(ctx, {frame_by_frame ? Strategy::FrameByFrame : Strategy::Single, sections}, sink);
    out.frames = std::move(sink.frames);
    out.steady = std::move(sink.steady);
    return out;
}

inline double rmse(const Image& a, const Image& b) {
    double s = 0;
    for (size_t i = 0; i < a.size(); ++i) s += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    return std::sqrt(s / static_cast<double>(a.size()));
}

inline double mean(const Image& a) {
    double s = 0;
    for (float v : a) s += v;
    return s / static_cast<double>(a.size());
}

inline MaterialDesc diffuse(const char* name, float albedo) {
    MaterialDesc m;
    m.name = name;
    m.albedo = Vec3(albedo);
    return m;
}

using test::quad;

inline LightDesc point_light(Vec3 p, float power) {
    LightDesc l;
    l.type = LightType::Point;
    l.position = p;
    l.power = Vec3(power);
    return l;
}

// A closed 2 m box with a quad light under its ceiling, seen from inside: the tests' Cornell
// box with every wall white (0.7).
inline SceneDesc closed_box(int res, int passes, int64_t photons, int max_depth = 8) {
    SceneDesc s = test::small_box(res, passes, photons, max_depth);
    s.source = "<hard box>";
    s.materials.resize(1);
    for (ShapeDesc& shape : s.shapes) shape.material = 0;
    return s;
}

using test::TempDir;

}  // namespace sl::hard
