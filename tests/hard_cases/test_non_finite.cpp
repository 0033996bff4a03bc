// The NaN/Inf guard: renders of ordinary and extreme inputs, and every value of every frame, of
// the steady image, and of the raw section buffers (accumulators, ambient, radii, photon counts)
// is counted; any non-finite value fails the test with the case's name.
#include <cmath>
#include <functional>

#include "foundation/errors.h"
#include "hard_helpers.h"

namespace sl::hard {
namespace {

struct GuardCase {
    const char* name;
    std::function<SceneDesc()> make;
    int sections = 1;
    bool frame_by_frame = false;
};

SceneDesc small(int res = 12, int passes = 4, int64_t photons = 3000) { return closed_box(res, passes, photons); }

MaterialDesc mirror(const char* name) {
    MaterialDesc m;
    m.name = name;
    m.type = MaterialType::Mirror;
    m.reflectance = Vec3(0.95f);
    return m;
}
MaterialDesc glass(const char* name) {
    MaterialDesc m;
    m.name = name;
    m.type = MaterialType::Dielectric;
    m.ior = 1.5f;
    return m;
}
ShapeDesc sphere(Vec3 c, float r, int material) {
    ShapeDesc s;
    s.type = ShapeType::Sphere;
    s.center = c;
    s.radius = r;
    s.material = material;
    return s;
}
LightDesc spot(Vec3 p, Vec3 dir, float cone_deg, float power) {
    LightDesc l;
    l.type = LightType::Spot;
    l.position = p;
    l.direction = dir;
    l.cone_deg = cone_deg;
    l.power = Vec3(power);
    return l;
}

// Scales every length of a scene (as `units` would) by f.
SceneDesc scaled(SceneDesc s, float f) {
    s.camera.position = s.camera.position * f;
    s.camera.look_at = s.camera.look_at * f;
    for (ShapeDesc& q : s.shapes) {
        q.corner = q.corner * f; q.edge1 = q.edge1 * f; q.edge2 = q.edge2 * f;
        q.center = q.center * f; q.radius *= f;
    }
    for (LightDesc& l : s.lights) {
        l.corner = l.corner * f; l.edge1 = l.edge1 * f; l.edge2 = l.edge2 * f;
        l.position = l.position * f;
    }
    s.meters_per_unit = f;
    return s;
}

std::vector<GuardCase> cases() {
    std::vector<GuardCase> c;
    c.push_back({"closed box", [] { return small(); }});
    c.push_back({"closed box, 4 sections", [] { return small(); }, 4});
    c.push_back({"closed box, frame by frame", [] { return small(); }, 1, true});
    c.push_back({"pulse emission of 3 frames", [] {
        SceneDesc s = small();
        s.emission.mode = EmissionMode::Pulse;
        s.emission.width_frames = 3;
        s.emission.width_ns = 3 * timeline_of(s).delta();
        return s;
    }, 3});
    c.push_back({"camera_tof and ambient", [] {
        SceneDesc s = small();
        s.render.camera_tof = true;
        s.render.ambient = Vec3(0.2f);
        return s;
    }});
    c.push_back({"albedo 1 everywhere, max_depth 60", [] {
        SceneDesc s = small();
        s.materials[0].albedo = Vec3(1);
        s.render.max_depth = 60;
        return s;
    }});
    c.push_back({"albedo 0 everywhere", [] {
        SceneDesc s = small();
        s.materials[0].albedo = Vec3(0);
        return s;
    }});
    c.push_back({"alpha 0.01", [] { SceneDesc s = small(); s.render.alpha = 0.01f; return s; }});
    c.push_back({"alpha 1", [] { SceneDesc s = small(); s.render.alpha = 1.0f; return s; }});
    c.push_back({"initial radius 1e-7 m", [] { SceneDesc s = small(); s.render.radius = 1e-7f; return s; }});
    c.push_back({"initial radius 100 m", [] { SceneDesc s = small(); s.render.radius = 100; return s; }});
    c.push_back({"2000 frames", [] { SceneDesc s = small(6, 3, 2000); s.time.frames = 2000; return s; }});
    c.push_back({"one frame of 1 fs", [] { SceneDesc s = small(); s.time = {3, 3.000001, 1, 24}; return s; }});
    c.push_back({"timeline far in the past and future", [] { SceneDesc s = small(); s.time = {-1e9, 1e9, 7, 24}; return s; }});
    c.push_back({"radiance 1e30", [] { SceneDesc s = small(); s.lights[0].radiance = Vec3(1e30f); return s; }});
    c.push_back({"a 1 micrometre box", [] { return scaled(small(), 1e-6f); }});
    c.push_back({"a 100,000 km box", [] { return scaled(small(), 5e7f); }});
    c.push_back({"point light on the floor", [] {
        SceneDesc s = small();
        s.lights = {point_light({0.1f, 0, 0.2f}, 10)};
        return s;
    }});
    c.push_back({"point light 1e-7 m above the floor", [] {
        SceneDesc s = small();
        s.lights = {point_light({0.1f, 1e-7f, 0.2f}, 10)};
        return s;
    }});
    c.push_back({"point light in a corner", [] {
        SceneDesc s = small();
        s.lights = {point_light({-1, 0, -1}, 10)};
        return s;
    }});
    c.push_back({"mirrors and glass, light inside the glass", [] {
        SceneDesc s = small(12, 4, 3000);
        s.materials.push_back(mirror("mirror"));
        s.materials.push_back(glass("glass"));
        s.shapes[2].material = 1;  // back wall: a mirror
        s.shapes.push_back(sphere({0, 1, 0}, 0.4f, 2));
        s.lights = {point_light({0, 1, 0}, 20)};
        s.render.camera_tof = true;
        return s;
    }});
    c.push_back({"camera inside a glass sphere", [] {
        SceneDesc s = small();
        s.materials.push_back(glass("glass"));
        s.shapes.push_back(sphere({0, 1, 0.99f}, 0.05f, 1));
        return s;
    }});
    c.push_back({"laser of radius 1 um", [] {
        SceneDesc s = small();
        LightDesc l;
        l.type = LightType::Laser;
        l.position = {0, 1, 0};
        l.direction = normalize(Vec3{0.3f, -1, -0.2f});
        l.radius = 1e-6f;
        l.power = Vec3(1);
        s.lights = {l};
        return s;
    }});
    c.push_back({"spot of 0.5 degrees", [] {
        SceneDesc s = small();
        s.lights = {spot({0, 1.9f, 0}, {0, -1, 0}, 0.5f, 10)};
        return s;
    }});
    c.push_back({"spot of 179 degrees", [] {
        SceneDesc s = small();
        s.lights = {spot({0, 1.9f, 0}, {0, -1, 0}, 179, 10)};
        return s;
    }});
    return c;
}

TEST(NonFiniteGuard, NoNaNOrInfInAnyBufferOfAnyRender) {
    size_t renders = 0, values = 0;
    for (const GuardCase& gc : cases()) {
        SCOPED_TRACE(gc.name);
        Rendered r = render(gc.make(), gc.sections, gc.frame_by_frame);
        ++renders;
        values += r.steady.size() * (r.frames.size() + 1);
        EXPECT_EQ(r.buffer_non_finite, 0u) << "non-finite values in the section buffers";
        EXPECT_EQ(r.image_non_finite(), 0u) << "non-finite values in frames or steady";
        EXPECT_TRUE(r.min_radius2 > 0 && std::isfinite(r.max_radius2)) << r.min_radius2 << " .. " << r.max_radius2;
    }
    EXPECT_GE(renders, 20u);
    EXPECT_GT(values, 0u);
}

}  // namespace
}  // namespace sl::hard

namespace sl::hard {
namespace {

// The largest power and radiance the scene file accepts (limits::kMaxEmission, 1e30) render
// without Inf or NaN: the estimates multiply them by 1/(pi r^2), BRDFs and sums over photons and
// passes in float, which overflowed near float's maximum (3e38, accepted before the bound).
TEST(NonFiniteGuard, LargestAcceptedPowerAndRadiance) {
    for (const char* light : {R"({"type": "point", "position": [0, 1.5, 0], "power": [1e30, 1e30, 1e30]})",
                              R"({"type": "quad", "corner": [-0.25, 1.98, -0.2], "edge1": [0.5, 0, 0],
                                  "edge2": [0, 0, 0.4], "radiance": [1e30, 1e30, 1e30]})"}) {
        const std::string text = R"({"camera": {"position": [0, 1, 0.99], "look_at": [0, 1, 0], "vfov_deg": 90,
            "width": 12, "height": 12},
          "materials": {"white": {"type": "diffuse", "albedo": [0.7, 0.7, 0.7]}},
          "shapes": [{"type": "box", "min": [-1, 0, -1], "max": [1, 2, 1], "material": "white"}],
          "lights": [)" + std::string(light) + R"(],
          "time": {"start_ns": 0, "end_ns": 24, "frames": 6},
          "render": {"passes": 4, "photons_per_pass": 3000}})";
        SceneDesc s = parse_scene_text(text, "bright.json", "");
        std::string beyond = text;
        beyond.replace(beyond.find("1e30"), 4, "3e38");
        EXPECT_THROW(parse_scene_text(beyond, "bright.json", ""), sl::InputError);
        Rendered r = render(s);
        EXPECT_EQ(r.buffer_non_finite, 0u) << light;
        EXPECT_EQ(r.image_non_finite(), 0u) << light;
    }
}

}  // namespace
}  // namespace sl::hard
