#include "pipeline/scene_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "config/text_util.h"
#include "core/import/mesh_data.h"
#include "core/import/mesh_instances.h"
#include "core/import/model_scene.h"
#include "core/shape_triangles.h"
#include "foundation/constants.h"
#include "foundation/message_lines.h"
#include "stages/render/render_context.h"

namespace sl {
namespace {

constexpr int kGrid = 64;            // camera rays per image side
constexpr int kEnclosureRays = 512;  // directions tried from the camera
constexpr double kUnitsSuspectM = 100;  // a scene larger than this, without units, is suspect

// Fibonacci sphere: n nearly uniform unit directions.
Vec3 sphere_direction(int i, int n) {
    const double golden = 2.39996322972865332;
    const double z = 1 - (2.0 * i + 1) / n, r = std::sqrt(std::max(0.0, 1 - z * z));
    return {static_cast<float>(r * std::cos(golden * i)), static_cast<float>(r * std::sin(golden * i)),
            static_cast<float>(z)};
}

struct Visible {
    Vec3 p, n;
    float camera_leg = 0;
};

std::vector<Visible> visible_points(const RenderContext& ctx) {
    std::vector<Visible> out;
    const Vec3 eye = ctx.camera.position();
    for (int j = 0; j < kGrid; ++j)
        for (int i = 0; i < kGrid; ++i) {
            const float px = (i + 0.5f) * ctx.width / kGrid, py = (j + 0.5f) * ctx.height / kGrid;
            const Vec3 d = ctx.camera.direction(px, py);
            SurfaceHit hit;
            if (!ctx.geometry.intersect(eye, d, 0, 1e30f, hit) || hit.light >= 0) continue;
            Vec3 n = dot(hit.normal, d) > 0 ? -hit.normal : hit.normal;
            out.push_back({hit.position, n, hit.t});
        }
    return out;
}

// The point of a quad light's parallelogram nearest to p (its plane coordinates, clamped).
Vec3 nearest_on_quad(const LightDesc& l, Vec3 p) {
    const Vec3 r = p - l.corner;
    const double a = dot(l.edge1, l.edge1), b = dot(l.edge1, l.edge2), c = dot(l.edge2, l.edge2);
    const double d = dot(r, l.edge1), e = dot(r, l.edge2), det = a * c - b * b;
    double u = det > 0 ? (c * d - b * e) / det : 0, v = det > 0 ? (a * e - b * d) / det : 0;
    u = std::clamp(u, 0.0, 1.0);
    v = std::clamp(v, 0.0, 1.0);
    return l.corner + l.edge1 * static_cast<float>(u) + l.edge2 * static_cast<float>(v);
}

}  // namespace

SceneFacts scene_facts(const RenderContext& ctx) {
    SceneFacts f;
    Vec3 lo = ctx.geometry.bounds_min(), hi = ctx.geometry.bounds_max();
    for (const LightDesc& l : ctx.scene.lights)
        if (l.type != LightType::Quad) {  // point-like lights count too (quads are geometry)
            lo = vmin(lo, l.position);
            hi = vmax(hi, l.position);
        }
    f.size = hi - lo;
    f.diagonal_m = length(f.size);
    f.crossing_ns = f.diagonal_m / kSpeedOfLight;
    f.triangles = ctx.geometry.triangle_count();
    for (const ShapeDesc& s : ctx.scene.shapes) f.spheres += s.type == ShapeType::Sphere;

    const bool tof = ctx.render.camera_tof;
    const std::vector<Visible> seen = visible_points(ctx);
    double first = 1e300, last = -1;
    for (size_t li = 0; li < ctx.scene.lights.size(); ++li) {
        const LightDesc& l = ctx.scene.lights[li];
        if (l.type == LightType::Laser) {  // a pencil: where its beam lands
            SurfaceHit hit;
            if (ctx.geometry.intersect(l.position, l.direction, 0, 1e30f, hit)) {
                double t = hit.t + (tof ? length(ctx.camera.position() - hit.position) : 0.0);
                first = std::min(first, t);
                last = std::max(last, t);
            }
            continue;
        }
        for (const Visible& v : seen) {
            if (l.type == LightType::Quad) {  // the nearest point of the quad it faces: the earliest
                const Vec3 n = cross(l.edge1, l.edge2);
                const Vec3 q = nearest_on_quad(l, v.p);
                if (dot(v.p - q, n) > 0) first = std::min<double>(first, length(v.p - q) + (tof ? v.camera_leg : 0.0f));
            }
            for (int s = 0; s < 9; ++s) {  // a 3 x 3 grid over an area light; one sample otherwise
                DirectLightSample d;
                if (!ctx.lights.sample_direct(li, v.p, v.n, (s % 3 + 0.5f) / 3, (s / 3 + 0.5f) / 3, d)) continue;
                const double t = d.distance + (tof ? v.camera_leg : 0.0f);
                if (l.type != LightType::Quad) first = std::min(first, t);
                const float eps = ray_epsilon(v.p, d.distance);
                if (!ctx.geometry.occluded(v.p + v.n * eps, d.to_light, 0, d.distance * (1 - 1e-4f)))
                    last = std::max(last, t);
                if (l.type != LightType::Quad) break;
            }
        }
    }
    // Emissive surfaces (imported, or a scene file's quads and boxes): one light after the
    // scene's own, sampled by power on an 8 x 8 grid of (u1, u2): the earliest arrival is that
    // of the nearest of 64 points on them, a little later than the true earliest.
    for (size_t li = ctx.scene.lights.size(); li < ctx.lights.count(); ++li)
        for (const Visible& v : seen)
            for (int s = 0; s < 64; ++s) {
                DirectLightSample d;
                if (!ctx.lights.sample_direct(li, v.p, v.n, (s % 8 + 0.5f) / 8, (s / 8 + 0.5f) / 8, d)) continue;
                const double t = d.distance + (tof ? v.camera_leg : 0.0f);
                first = std::min(first, t);
                const float eps = ray_epsilon(v.p, d.distance);
                if (!ctx.geometry.occluded(v.p + v.n * eps, d.to_light, 0, d.distance * (1 - 1e-4f)))
                    last = std::max(last, t);
            }
    if (first < 1e300) f.first_arrival_ns = first / kSpeedOfLight;
    if (last >= 0) f.last_direct_arrival_ns = last / kSpeedOfLight;

    // A closed room: no direction from the camera escapes. A light outside the box of the
    // room's walls (as the camera sees them all around) cannot light anything inside it.
    Vec3 room_lo{1e30f}, room_hi{-1e30f};
    f.camera_enclosed = true;
    for (int i = 0; i < kEnclosureRays && f.camera_enclosed; ++i) {
        SurfaceHit hit;
        if (!ctx.geometry.intersect(ctx.camera.position(), sphere_direction(i, kEnclosureRays), 0, 1e30f, hit))
            f.camera_enclosed = false;
        else {
            room_lo = vmin(room_lo, hit.position);
            room_hi = vmax(room_hi, hit.position);
        }
    }
    if (f.camera_enclosed) {
        const float slack = 1e-3f * length(room_hi - room_lo);
        for (size_t li = 0; li < ctx.scene.lights.size(); ++li) {
            const LightDesc& l = ctx.scene.lights[li];
            Vec3 c = l.type == LightType::Quad ? l.corner + (l.edge1 + l.edge2) * 0.5f : l.position;
            bool inside = true;
            for (int a = 0; a < 3; ++a) inside = inside && c[a] >= room_lo[a] - slack && c[a] <= room_hi[a] + slack;
            if (!inside) f.lights_outside.push_back(static_cast<int>(li));
        }
    }
    return f;
}

double light_watts(const LightDesc& l, Vec3 size) {
    auto mean = [](Vec3 v) { return (double(v.x) + v.y + v.z) / 3; };
    switch (l.type) {
        case LightType::Quad: return mean(l.radiance) * kPiDouble * length(cross(l.edge1, l.edge2));
        case LightType::Sun: {
            const Vec3 d = normalize(l.direction);
            const double area = std::abs(d.x) * size.y * size.z + std::abs(d.y) * size.x * size.z +
                                std::abs(d.z) * size.x * size.y;
            return mean(l.irradiance) * area;
        }
        default: return mean(l.power);
    }
}

double emissive_watts(const SceneDesc& s, const ShapeDesc& shape) {
    // Each placed copy of a mesh held once emits as a copy in the scene would.
    auto watts = [&](const MeshData& m, const Affine* placed) {
        double w = 0;
        for (size_t t = 0; t < m.tri_material.size(); ++t) {
            const MaterialDesc& mat = s.materials[static_cast<size_t>(m.tri_material[t])];
            if (!mat.emits()) continue;
            Vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                 c = m.positions[m.indices[3 * t + 2]];
            if (placed) { a = placed->point(a); b = placed->point(b); c = placed->point(c); }
            const double area = 0.5 * length(cross(b - a, c - a));
            w += (double(mat.emission.x) + mat.emission.y + mat.emission.z) / 3 * kPiDouble * area *
                 (mat.double_sided ? 2 : 1);
        }
        return w;
    };
    double w = shape.mesh ? watts(*shape.mesh, nullptr) : 0;
    if (!shape.mesh && !shape.instances && shape.type != ShapeType::Sphere && shape.material >= 0 &&
        s.materials[static_cast<size_t>(shape.material)].emits()) {
        // A scene file's quad or box of an emissive material: its triangles, as the emitters hold them.
        const TriangleSoup soup = triangulate_shape(shape);
        MeshData m;
        m.positions = soup.vertices;
        m.indices = soup.indices;
        m.tri_material.assign(soup.indices.size() / 3, shape.material);
        w = watts(m, nullptr);
    }
    if (shape.instances)
        for (const InstancedMesh& im : shape.instances->meshes)
            for (const Affine& a : im.placements) w += watts(*im.mesh, &a);
    return w;
}

namespace {

// A glTF file whose lamps and emissive surfaces differ by more than kLightScaleSuspect: the
// lamps were most likely written in the other unit (W/sr against cd: 683).
void light_scale_warnings(const SceneDesc& s, Vec3 size, std::vector<std::string>& w) {
    const bool model_alone = is_model_file(s.source);
    for (const ShapeDesc& sh : s.shapes) {
        if (sh.type != ShapeType::Gltf || sh.light_count == 0) continue;
        double lamps = 0;
        for (int i = sh.first_light; i < sh.first_light + sh.light_count; ++i)
            lamps += light_watts(s.lights[static_cast<size_t>(i)], size);
        const double surfaces = emissive_watts(s, sh);
        if (!(lamps > 0) || !(surfaces > 0)) continue;
        const double ratio = lamps / surfaces;
        if (ratio <= kLightScaleSuspect && ratio >= 1 / kLightScaleSuspect) continue;
        const bool radiometric = sh.light_units == LightUnits::Radiometric;
        const bool lamps_weak = ratio < 1;
        std::string advice;
        const std::string key = model_alone ? "render it with --gltf-light-units " : "give its gltf shape \"light_units\": ";
        if (lamps_weak && !radiometric)
            advice = "if its lights are in W/sr and W/m^2 (Blender's \"Unitless\" lighting mode), " + key +
                     (model_alone ? "radiometric" : "\"radiometric\"");
        else if (!lamps_weak && radiometric)
            advice = "if its lights are in candela and lux (Blender's \"Standard\" lighting mode), " + key +
                     (model_alone ? "photometric" : "\"photometric\"");
        else
            advice = std::string("check the file's light intensities and emission strengths (its lights are read as ") +
                     (radiometric ? "W/sr and W/m^2" : "candela and lux") + ")";
        char buf[1024];
        std::snprintf(buf, sizeof buf,
                      "warning: %s: its lamps emit %.4g W and its emissive surfaces %.4g W, %.0f times %s: one of them "
                      "is almost certainly in the other unit; %s",
                      sh.file.c_str(), lamps, surfaces, lamps_weak ? 1 / ratio : ratio, lamps_weak ? "less" : "more",
                      advice.c_str());
        w.push_back(buf);
    }
}

}  // namespace

std::vector<std::string> scene_warnings(const RenderContext& ctx, const SceneFacts& f) {
    std::vector<std::string> w;
    const SceneDesc& s = ctx.scene;
    char buf[512];
    if (f.diagonal_m > kUnitsSuspectM && s.meters_per_unit == 1 && f.crossing_ns > s.time.end_ns) {
        std::snprintf(buf, sizeof buf,
                      "warning: %s: the scene is %.0f m across (no \"units\", so coordinates are meters): light needs "
                      "%.0f ns to cross it, and the video ends at %s ns; if the coordinates are centimeters, add "
                      "\"units\": {\"meters_per_unit\": 0.01}",
                      s.source.c_str(), f.diagonal_m, f.crossing_ns, format_number(s.time.end_ns).c_str());
        w.push_back(buf);
    }
    for (int li : f.lights_outside) {
        std::snprintf(buf, sizeof buf,
                      "warning: %s: lights[%d] is outside the closed room the camera is in: none of its light can "
                      "reach what the camera sees",
                      s.source.c_str(), li);
        w.push_back(buf);
    }
    // In a medium the air itself lights up at once: only surfaces can arrive too late.
    if (!s.medium.present && f.first_arrival_ns && *f.first_arrival_ns >= s.time.end_ns &&
        f.lights_outside.empty()) {
        std::snprintf(buf, sizeof buf,
                      "warning: %s: nothing but the lights themselves arrives before end_ns = %s ns: the first light "
                      "reflected toward the camera arrives at about %.3g ns; raise time.end_ns",
                      s.source.c_str(), format_number(s.time.end_ns).c_str(), *f.first_arrival_ns);
        w.push_back(buf);
    }
    light_scale_warnings(s, f.size, w);
    // One line each, at most kMaxMessageLine characters (a source name can be a megabyte), a
    // repeated one once with its count.
    std::vector<std::string> lines;
    for (const std::string& l : counted_lines(w))
        lines.push_back(message_line("warning: ", l.rfind("warning: ", 0) == 0 ? l.substr(9) : l));
    return lines;
}

}  // namespace sl
