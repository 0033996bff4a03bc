// The scene file's "emission" key on a material (W sr^-1 m^-2 from the front): the surface is an
// area light. Its energy is checked two independent ways:
// - direct light: a floor under an emissive 1 m square (max_depth 1) shows rho * L * F at each
//   point, F the view factor of the square seen from the point (the parallel-rectangle formula),
//   so the light leaving the square is L per unit projected area and solid angle;
// - photons: a closed room lit by an emissive quad renders as the same room lit by a quad light
//   of the same radiance (whose power, L pi A, other tests check), bounces and all; its power in
//   the light set is L pi A.
#include <gtest/gtest.h>

#include <cmath>

#include "config/parse_scene.h"
#include "core/light_set.h"
#include "foundation/errors.h"
#include "tests/render/render_helpers.h"
#include "tests/render/scenes_for_tests.h"

namespace sl::test {
namespace {

// View factor from a point to the rectangle [0, X] x [0, Y] (in units of its height h) of a
// parallel plane, the point below the corner (0, 0); odd in X and in Y.
double corner_factor(double X, double Y) {
    const double a = std::sqrt(1 + X * X), b = std::sqrt(1 + Y * Y);
    return (X / a * std::atan(Y / a) + Y / b * std::atan(X / b)) / (2 * kPiDouble);
}

// The view factor of [x0, x1] x [z0, z1] at height h, from the point (px, pz) below it.
double rect_factor(double x0, double x1, double z0, double z1, double h, double px, double pz) {
    auto f = [&](double x, double z) { return corner_factor((x - px) / h, (z - pz) / h); };
    return f(x1, z1) - f(x0, z1) - f(x1, z0) + f(x0, z0);
}

MaterialDesc emitter(Vec3 radiance) {
    MaterialDesc m;
    m.name = "lamp";
    m.albedo = Vec3(0);
    m.emission = radiance;
    return m;
}

TEST(EmissiveMaterial, FloorUnderAnEmissiveSquareGetsTheViewFactorIrradiance) {
    const float rho = 0.5f, L = 3.0f, h = 1.0f, cam_h = 0.8f;
    const int res = 16;
    SceneDesc s = plane_under_point_light(rho, 0, 1, cam_h, res, 20);
    s.lights.clear();
    s.materials.push_back(emitter(Vec3(L)));
    // 1 m square at height h, facing down (edge1 x edge2 = -y).
    s.shapes.push_back(quad({-0.5f, h, -0.5f}, {1, 0, 0}, {0, 0, 1}, 1));
    s.render.passes = 1024;  // one light sample per pixel and pass: ~2 % noise per pixel
    s.render.photons_per_pass = 100;  // none is stored (max_depth 1: direct light only)
    const Rendered r = render_all(s);
    double sum = 0, want_sum = 0;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            // Pixel centre -> floor point (camera looking straight down, 90 degrees, up = -z).
            const double px = cam_h * (2 * (x + 0.5) / res - 1), pz = cam_h * (2 * (y + 0.5) / res - 1);
            const double want = rho * L * rect_factor(-0.5, 0.5, -0.5, 0.5, h, px, pz);
            const double got = r.steady[3 * (static_cast<size_t>(y) * res + static_cast<size_t>(x))];
            EXPECT_NEAR(got, want, 0.06 * want) << "pixel " << x << ", " << y;
            sum += got;
            want_sum += want;
        }
    EXPECT_NEAR(sum, want_sum, 0.01 * want_sum);
}

TEST(EmissiveMaterial, EmissiveQuadLightsARoomAsAQuadLightOfItsRadianceDoes) {
    SceneDesc with_light = small_box(24, 16, 40000);
    SceneDesc with_material = with_light;
    const LightDesc l = with_light.lights[0];
    with_material.lights.clear();
    with_material.materials.push_back(emitter(l.radiance));
    with_material.shapes.push_back(quad(l.corner, l.edge1, l.edge2, static_cast<int>(with_material.materials.size() - 1)));

    // Its power, as the light set holds it: L pi A (one-sided), the quad light's.
    const SceneDesc resolved = with_imports(with_material);
    const double area = length(cross(l.edge1, l.edge2));
    EXPECT_NEAR(LightSet(resolved).total_power(), average(l.radiance) * kPiDouble * area, 1e-4 * average(l.radiance) * area);
    EXPECT_NEAR(LightSet(resolved).total_power(), LightSet(with_light).total_power(), 1e-5 * LightSet(with_light).total_power());

    const Rendered a = render_all(with_light), b = render_all(with_material);
    for (int c = 0; c < 3; ++c) {
        double sa = 0, sb = 0;
        for (size_t i = static_cast<size_t>(c); i < a.steady.size(); i += 3) {
            sa += a.steady[i];
            sb += b.steady[i];
        }
        ASSERT_GT(sa, 0);
        EXPECT_NEAR(sb, sa, 0.02 * sa) << "channel " << c;
    }
    // And in time: the frames' totals agree as well (the emitter switches on at t = 0 as a light does).
    for (size_t f = 0; f < a.frames.size(); ++f) {
        const double ma = mean(a.frames[f]), mb = mean(b.frames[f]);
        EXPECT_NEAR(mb, ma, 0.05 * ma + 1e-9) << "frame " << f;
    }
}

TEST(EmissiveMaterial, TheSceneFileKeyAndASphereRefused) {
    const std::string head = R"({"camera": {"position": [0, 1, 3], "look_at": [0, 1, 0]},
      "materials": {"lamp": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [1, 2, 3]},
                    "wall": {"type": "conductor", "roughness": 0.3, "emission": [0.5, 0.5, 0.5]}},
      "shapes": [)";
    const SceneDesc s = parse_scene_text(head + R"({"type": "quad", "corner": [0, 2, 0], "edge1": [1, 0, 0],
      "edge2": [0, 0, 1], "material": "lamp"}]})", "lamp.json", ".");
    EXPECT_EQ(s.materials[0].emission.x, 1);
    EXPECT_EQ(s.materials[0].emission.z, 3);
    EXPECT_EQ(s.materials[1].emission.y, 0.5f);
    EXPECT_NO_THROW(with_imports(s));  // lit by its emissive quad alone: no "no light" error
    try {
        parse_scene_text(head + R"({"type": "sphere", "center": [0, 1, 0], "radius": 0.5, "material": "lamp"}]})",
                         "ball.json", ".");
        ADD_FAILURE() << "an emissive sphere was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("a sphere cannot emit"), std::string::npos) << e.what();
    }
    std::string negative = head + R"({"type": "quad", "corner": [0, 2, 0], "edge1": [1, 0, 0], "edge2": [0, 0, 1],
      "material": "lamp"}]})";
    negative.replace(negative.find("[1, 2, 3]"), 9, "[1, -2, 3]");
    try {
        parse_scene_text(negative, "negative.json", ".");
        ADD_FAILURE() << "a negative emission was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("emission"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace sl::test
