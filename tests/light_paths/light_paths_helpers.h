#pragma once
// Helpers for the light-path physics tests (issue 6): scenes built in code and an in-process
// render of the whole timeline (the program's own render, frames kept in memory), plus
// per-pixel arrival-time measurements.
#include <cmath>
#include <vector>

#include "core/import/resolve_imports.h"
#include "config/scene_desc.h"
#include "core/camera.h"
#include "core/sampling.h"
#include "pipeline/frames_in_memory.h"
#include "pipeline/render_frames.h"
#include "stages/render/render_context.h"
#include "tests/render/scenes_for_tests.h"

namespace sl::lp {

inline constexpr double kC = 0.299792458;  // m/ns, the speed of light

struct Rendered {
    std::vector<std::vector<float>> frames;  // one RGB image per frame, row 0 at the top
    std::vector<float> steady;
    int width = 0, height = 0;
    float pixel(int f, int x, int y, int c = 0) const { return frames[f][(size_t(y) * width + x) * 3 + c]; }
    float steady_at(int x, int y, int c = 0) const { return steady[(size_t(y) * width + x) * 3 + c]; }
};

// One whole-timeline convergence (a single section), frames assembled in the scene's own mode.
inline Rendered render_all(const SceneDesc& scene) {
    RenderContext ctx(with_imports(scene));  // imported files read first, as the program does
    Rendered out;
    out.width = ctx.width;
    out.height = ctx.height;
    FramesInMemory sink;
    render_frames(ctx, {}, sink);
    out.frames = std::move(sink.frames);
    out.steady = std::move(sink.steady);
    return out;
}

// The steady image of a scene lit without end (constant emission), after tweak(ctx) has set
// the RenderContext switch a test compares (independent numbers against stratified ones).
template <class Tweak>
std::vector<float> steady_image(SceneDesc s, int max_depth, int passes, int64_t photons, uint64_t seed, Tweak&& tweak) {
    s.time = {0, 12, 12, 24};
    s.emission.mode = EmissionMode::Constant;
    s.render.max_depth = max_depth;
    s.render.passes = passes;
    s.render.photons_per_pass = photons;
    s.render.seed = seed;
    RenderContext ctx(with_imports(s));
    tweak(ctx);
    FramesInMemory sink;
    render_frames(ctx, {}, sink);
    return sink.steady;
}

// A scene with one material list and no shapes yet; pulse emission of one bucket unless told.
inline SceneDesc empty_scene(Vec3 cam_pos, Vec3 look_at, Vec3 up, float vfov, int res) {
    SceneDesc s;
    s.source = "<light-path test>";
    s.camera.position = cam_pos;
    s.camera.look_at = look_at;
    s.camera.up = up;
    s.camera.vfov_deg = vfov;
    s.camera.width = s.camera.height = res;
    s.emission.mode = EmissionMode::Pulse;
    s.emission.width_frames = 1;
    s.render.max_depth = 1;
    s.render.passes = 4;
    s.render.photons_per_pass = 1000;
    return s;
}

inline int add_material(SceneDesc& s, MaterialType type, Vec3 albedo_or_reflectance, float ior = 1.5f) {
    MaterialDesc m;
    m.name = "m" + std::to_string(s.materials.size());
    m.type = type;
    m.albedo = albedo_or_reflectance;
    m.reflectance = albedo_or_reflectance;
    m.ior = ior;
    s.materials.push_back(m);
    return static_cast<int>(s.materials.size()) - 1;
}

inline void add_quad(SceneDesc& s, Vec3 corner, Vec3 e1, Vec3 e2, int material) {
    s.shapes.push_back(test::quad(corner, e1, e2, material));
}

inline void add_box(SceneDesc& s, Vec3 lo, Vec3 hi, int material) {
    ShapeDesc b;
    b.type = ShapeType::Box;
    b.min = lo;
    b.max = hi;
    b.material = material;
    s.shapes.push_back(b);
}

inline void add_point_light(SceneDesc& s, Vec3 p, float power) {
    LightDesc l;
    l.type = LightType::Point;
    l.position = p;
    l.power = Vec3(power);
    s.lights.push_back(l);
}

inline void add_spot(SceneDesc& s, Vec3 p, Vec3 dir, float cone_deg, float power) {
    LightDesc l;
    l.type = LightType::Spot;
    l.position = p;
    l.direction = normalize(dir);
    l.cone_deg = cone_deg;
    l.power = Vec3(power);
    s.lights.push_back(l);
}

inline void add_laser(SceneDesc& s, Vec3 p, Vec3 dir, float radius, float power) {
    LightDesc l;
    l.type = LightType::Laser;
    l.position = p;
    l.direction = normalize(dir);
    l.radius = radius;
    l.power = Vec3(power);
    s.lights.push_back(l);
}

// Where the camera ray through image point (fx, fy) meets the plane dot(n, x) = offset; the ray
// parameter is returned in `t` (negative or infinite when it misses).
inline Vec3 on_plane(const PinholeCamera& cam, float fx, float fy, Vec3 n, float offset, float* t_out = nullptr) {
    Vec3 d = cam.direction(fx, fy);
    float t = (offset - dot(n, cam.position())) / dot(n, d);
    if (t_out) *t_out = t;
    return cam.position() + d * t;
}

// Per pixel arrival measurements over the pulse frames of channel 0.
struct Arrival {
    int first = -1;     // first frame with any light (-1: never lit)
    double mean = -1;   // energy-weighted mean frame index (-1: never lit)
    double total = 0;   // sum over frames
};

inline Arrival arrival(const Rendered& r, int x, int y) {
    Arrival a;
    double wsum = 0;
    for (int f = 0; f < static_cast<int>(r.frames.size()); ++f) {
        double v = r.pixel(f, x, y);
        if (v > 0 && a.first < 0) a.first = f;
        a.total += v;
        wsum += v * f;
    }
    if (a.total > 0) a.mean = wsum / a.total;
    return a;
}

// The frame (bucket) index of arrival time t for a timeline starting at 0 with width delta.
inline int bucket_of(double t_ns, double delta) { return static_cast<int>(std::floor(t_ns / delta)); }

}  // namespace sl::lp
