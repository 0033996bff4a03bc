// Lights at their extremes: a very bright light beside a very dim one (ten orders of magnitude
// apart, both must show, each at its analytic value), and light grazing a quad (at 1e-2 and
// 1e-4 rad it must match the analytic irradiance, and never leak to the other side).
#include <cmath>

#include "foundation/errors.h"
#include "core/camera.h"
#include "core/sampling.h"
#include "hard_helpers.h"

namespace sl::hard {
namespace {

// Radiance of a diffuse plane y = 0 (albedo rho) lit directly by a point light of power P at
// (lx, h, lz), averaged over the ground footprint of pixel (x, y) of a camera looking straight
// down (sub-sampled 16 x 16).
double expected_pixel(const SceneDesc& s, int x, int y, float rho, float P, Vec3 light) {
    PinholeCamera cam(s.camera);
    double sum = 0;
    const int n = 16;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            Vec3 d = cam.direction(x + (i + 0.5f) / n, y + (j + 0.5f) / n);
            double t = -double(cam.position().y) / d.y;
            double gx = cam.position().x + t * d.x, gz = cam.position().z + t * d.z;
            double dx = gx - light.x, dz = gz - light.z, h = light.y;
            double r2 = dx * dx + dz * dz + h * h;
            sum += rho / kPi * (P / (4 * kPi)) * h / (r2 * std::sqrt(r2));
        }
    return sum / (n * n);
}

// The pixel whose footprint contains ground point (gx, gz), for a camera looking straight down.
void pixel_of(const SceneDesc& s, double gx, double gz, int& x, int& y) {
    const CameraDesc& c = s.camera;
    double H = c.position.y, half_h = std::tan(c.vfov_deg * kPi / 360.0), half_w = half_h * c.width / c.height;
    double sx = (gx - c.position.x) / H, sy = -(gz - c.position.z) / H;  // right = +x, image up = -z
    x = static_cast<int>(std::floor((sx / half_w + 1) * c.width / 2));
    y = static_cast<int>(std::floor((1 - sy / half_h) * c.height / 2));
}

SceneDesc looking_down(Vec3 at, float height, float vfov, int res) {
    SceneDesc s;
    s.source = "<hard: looking down>";
    s.camera.position = {at.x, height, at.z};
    s.camera.look_at = at;
    s.camera.up = {0, 0, -1};
    s.camera.vfov_deg = vfov;
    s.camera.width = s.camera.height = res;
    s.materials = {diffuse("grey", 0.5f)};
    s.time = {0, 100, 4, 24};
    return s;
}

TEST(BrightBesideDim, BothVisibleAtTheirAnalyticValues) {
    const float bright = 1e8f, dim = 1e-2f, h = 0.4f, rho = 0.5f;
    const Vec3 lb{-1, h, 0}, ld{1, h, 0};
    SceneDesc s = looking_down({0, 0, 0}, 4, 60, 64);
    s.shapes = {quad({-2, 0, 1}, {4, 0, 0}, {0, 0, -2}),     // floor
                quad({0, 0, -1}, {0, 0, 2}, {0, 1, 0})};      // a wall between the two lights
    s.lights = {point_light(lb, bright), point_light(ld, dim)};
    for (int depth : {1, 8}) {
        // Direct light only: many cheap passes, so that the pixels' jitter averages out (the
        // radiance changes by ~25% across a pixel here). With photons: fewer, fuller passes.
        s.render.max_depth = depth;
        s.render.passes = depth == 1 ? 512 : 64;
        s.render.photons_per_pass = depth == 1 ? 100 : 20000;
        Rendered r = render(s);
        ASSERT_EQ(r.buffer_non_finite, 0u) << "max_depth " << depth;
        ASSERT_EQ(r.image_non_finite(), 0u) << "max_depth " << depth;
        for (auto [l, P] : {std::pair{lb, bright}, std::pair{ld, dim}}) {
            for (double off : {0.0, 0.3, -0.5}) {  // under the light and beside it
                int x, y;
                pixel_of(s, l.x + off, 0.25, x, y);
                double want = expected_pixel(s, x, y, rho, P, l);
                double got = r.px(r.steady, x, y)[1];
                SCOPED_TRACE(::testing::Message() << "light of " << P << " W, offset " << off << ", max_depth " << depth
                                                  << ", pixel (" << x << ", " << y << ")");
                if (depth == 1) {
                    EXPECT_NEAR(got, want, 0.015 * want);
                } else {
                    // With photons, indirect light adds (bright side: from the wall) but the
                    // direct part is never lost, however dim the light beside the bright one.
                    EXPECT_GE(got, 0.95 * want);
                    EXPECT_LE(got, 1.5 * want);
                }
            }
        }
    }
}

TEST(GrazingLight, MatchesAnalyticIrradianceAndDoesNotLeak) {
    const float rho = 0.5f, P = 100;
    for (float h : {1e-2f, 1e-4f}) {
        // The camera sees ground x in [1.5, 2.5]: the light arrives at 1/200 .. 1/25000 rad.
        SceneDesc s = looking_down({2, 0, 0}, 1, 53.13f, 32);
        s.shapes = {quad({-50, 0, 50}, {100, 0, 0}, {0, 0, -100})};
        const Vec3 light{0, h, 0};
        s.lights = {point_light(light, P)};
        s.render.passes = 16;
        s.render.photons_per_pass = 2000;
        s.render.max_depth = 1;
        Rendered top = render(s);
        ASSERT_EQ(top.buffer_non_finite + top.image_non_finite(), 0u);
        for (int y : {2, 16, 29})
            for (int x : {1, 16, 30}) {
                double want = expected_pixel(s, x, y, rho, P, light);
                EXPECT_NEAR(top.px(top.steady, x, y)[0], want, 0.03 * want)
                    << "height " << h << ", pixel (" << x << ", " << y << ")";
            }
        // From below, the plane's other side is dark, photons (max_depth 8) included.
        s.camera.position = {2, -1, 0};
        s.camera.up = {0, 0, 1};
        s.render.max_depth = 8;
        Rendered below = render(s);
        ASSERT_EQ(below.buffer_non_finite + below.image_non_finite(), 0u);
        double leak = 0;
        for (float v : below.steady) leak = std::max(leak, double(v));
        EXPECT_EQ(leak, 0.0) << "light leaked through the plane at height " << h;
    }
}

TEST(GrazingLight, QuadLightStandingOnAFloor) {
    // A quad light standing on the floor and facing +z: the floor in front is lit at grazing
    // angles near the light's base, the floor behind it not at all.
    SceneDesc s = looking_down({0, 0, 0}, 3, 60, 48);
    s.shapes = {quad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4})};
    LightDesc l;
    l.type = LightType::Quad;
    l.corner = {-0.5f, 0, 0};
    l.edge1 = {1, 0, 0};
    l.edge2 = {0, 0.5f, 0};  // edge1 x edge2 = +z
    l.radiance = Vec3(10);
    s.lights = {l};
    s.render.passes = 16;
    s.render.photons_per_pass = 5000;
    Rendered r = render(s);
    ASSERT_EQ(r.buffer_non_finite + r.image_non_finite(), 0u);
    int x, y_front, y_near, y_back;
    pixel_of(s, 0, 0.6, x, y_front);
    pixel_of(s, 0, 0.1, x, y_near);
    pixel_of(s, 0, -0.6, x, y_back);
    double front = r.px(r.steady, x, y_front)[0], near = r.px(r.steady, x, y_near)[0];
    EXPECT_GT(front, 0.0);
    EXPECT_GT(near, front);  // closer to the light, more light (grazing or not)
    // Behind the light: direct light is impossible; only photons bounced off the lit floor,
    // which cannot get behind the light in one open plane either.
    EXPECT_EQ(r.px(r.steady, x, y_back)[0], 0.0f);
}

}  // namespace
}  // namespace sl::hard

namespace sl::hard {
namespace {

// A spot light straight above a plane, seen from above inside its cone: the radiance on the
// axis is rho/pi * I / h^2 with I = P / (2 pi (1 - cos(cone))), computed here in double.
double spot_on_axis(const std::string& cone_deg, double& got_max, size_t& non_finite) {
    const std::string text = R"({"camera": {"position": [0, 0.5, 0], "look_at": [0, 0, 0], "up": [0, 0, -1],
        "vfov_deg": 0.002, "width": 8, "height": 8},
      "materials": {"grey": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
      "shapes": [{"type": "quad", "corner": [-5, 0, 5], "edge1": [10, 0, 0], "edge2": [0, 0, -10], "material": "grey"}],
      "lights": [{"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "cone_deg": )" + cone_deg +
                             R"(, "power": [1, 1, 1]}],
      "time": {"start_ns": 0, "end_ns": 10, "frames": 2},
      "render": {"passes": 4, "photons_per_pass": 1000, "max_depth": 1}})";
    SceneDesc s = parse_scene_text(text, "spot.json", "");
    Rendered r = render(s);
    non_finite = r.buffer_non_finite + r.image_non_finite();
    got_max = 0;
    for (size_t i = 0; i < r.steady.size(); i += 3) got_max = std::max(got_max, double(r.steady[i]));
    const double theta = std::stod(cone_deg) * kPi / 180;
    const double one_minus_cos = 2 * std::sin(theta / 2) * std::sin(theta / 2);
    return 0.5 / kPi * 1.0 / (2 * kPi * one_minus_cos);  // h = 1
}

TEST(NarrowSpot, FiveDegreesAndHalfADegreeMatchTheAnalyticIntensity) {
    for (const char* cone : {"5", "0.5"}) {
        double got, want;
        size_t bad;
        want = spot_on_axis(cone, got, bad);
        EXPECT_EQ(bad, 0u) << cone << " degrees";
        EXPECT_NEAR(got, want, 0.01 * want) << cone << " degrees";
    }
}

// Narrower cones are lasers: 1 - cos(cone) vanishes in float below ~0.02 degrees (the intensity
// became infinite). The parser refuses cones under 0.1 degrees; at 0.1 the intensity is exact.
TEST(NarrowSpot, ATenthOfADegreeIsExactAndNarrowerIsRefused) {
    double got, want;
    size_t bad;
    want = spot_on_axis("0.1", got, bad);
    EXPECT_EQ(bad, 0u);
    EXPECT_NEAR(got, want, 0.01 * want);
    for (const char* cone : {"0.05", "0.01", "0.001"}) {
        EXPECT_THROW(spot_on_axis(cone, got, bad), sl::InputError) << cone << " degrees";
    }
}

}  // namespace
}  // namespace sl::hard
