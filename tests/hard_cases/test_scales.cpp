// The same scene at 1 mm and at 10 km (`units.meters_per_unit`): the front of a point light's
// direct light, sweeping over a plane, is in the right frame at both scales, to a hundredth of
// a frame's width. Each pixel whose whole footprint lies inside the front (by 1% of a bucket)
// shows all its light in the constant frame; each pixel wholly outside shows none of it.
#include <cmath>
#include <sstream>

#include "core/camera.h"
#include "hard_helpers.h"

namespace sl::hard {
namespace {

// A 10 x 10 unit plane, a point light 2 units above its middle, a camera 5 units above
// looking straight down at it; frames of width cΔ = 0.5 units of light travel from t = 0.
std::string plane_scene(double meters_per_unit, int frames, double delta_ns, const char* emission) {
    std::ostringstream j;
    j.precision(17);
    j << R"({"units": {"meters_per_unit": )" << meters_per_unit << R"(},
      "camera": {"position": [0, 5, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "vfov_deg": 90,
                 "width": 40, "height": 40},
      "materials": {"grey": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
      "shapes": [{"type": "quad", "corner": [-5, 0, 5], "edge1": [10, 0, 0], "edge2": [0, 0, -10],
                  "material": "grey"}],
      "lights": [{"type": "point", "position": [0, 2, 0], "power": [100, 100, 100]}],
      "time": {"start_ns": 0, "end_ns": )" << frames * delta_ns << R"(, "frames": )" << frames << R"(},
      "emission": {"mode": ")" << emission << R"("},
      "render": {"passes": 8, "photons_per_pass": 100, "max_depth": 1, "seed": 3}})";
    return j.str();
}

struct FrontCheck {
    int inside = 0, outside = 0, straddling = 0;
};

// Checks every frame of a constant-emission render against the front of the direct light.
FrontCheck check_fronts(const SceneDesc& s, const Rendered& r, double tol_fraction) {
    RenderContext ctx(s);  // for the camera and the timeline, exactly as rendered
    const Timeline& tl = ctx.timeline;
    const Vec3 cam = ctx.camera.position();
    const Vec3 light = s.lights[0].position;
    const double c = kSpeedOfLight, tol = tol_fraction * tl.delta() * c;
    const double half = 5 * s.meters_per_unit;  // the plane's half size in meters
    FrontCheck out;
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            // The pixel's footprint on the plane (a rectangle: the plane faces the camera).
            double lo_x = 1e300, hi_x = -1e300, lo_z = 1e300, hi_z = -1e300;
            for (int corner = 0; corner < 4; ++corner) {
                Vec3 d = ctx.camera.direction(float(x + corner % 2), float(y + corner / 2));
                double t = -double(cam.y) / d.y;
                double gx = cam.x + t * d.x, gz = cam.z + t * d.z;
                lo_x = std::min(lo_x, gx); hi_x = std::max(hi_x, gx);
                lo_z = std::min(lo_z, gz); hi_z = std::max(hi_z, gz);
            }
            if (lo_x < -half || hi_x > half || lo_z < -half || hi_z > half) continue;  // off the plane
            auto dist = [&](double gx, double gz) {
                double dx = gx - light.x, dy = double(light.y), dz = gz - light.z;
                return std::sqrt(dx * dx + dy * dy + dz * dz);
            };
            double near = dist(std::clamp(double(light.x), lo_x, hi_x), std::clamp(double(light.z), lo_z, hi_z));
            double far = 0;
            for (double gx : {lo_x, hi_x})
                for (double gz : {lo_z, hi_z}) far = std::max(far, dist(gx, gz));
            const float* steady = r.px(r.steady, x, y);
            EXPECT_GT(steady[0], 0.0f) << "pixel " << x << "," << y;
            for (int k = 0; k < tl.frames; ++k) {
                const double front = c * tl.edge(k + 1);  // light arrived by the frame's end
                const float* v = r.px(r.frames[k], x, y);
                if (far < front - tol) {
                    ++out.inside;
                    EXPECT_NEAR(v[0], steady[0], 1e-5 * steady[0]) << "frame " << k << ", pixel " << x << "," << y;
                } else if (near >= front + tol) {
                    ++out.outside;
                    EXPECT_EQ(v[0], 0.0f) << "frame " << k << ", pixel " << x << "," << y;
                } else {
                    ++out.straddling;
                }
            }
        }
    return out;
}

class Scales : public ::testing::TestWithParam<double> {};

TEST_P(Scales, DirectLightFrontInTheRightFrame) {
    const double mpu = GetParam();
    const double delta_ns = 0.5 * mpu / kSpeedOfLight;  // half a unit of light travel per frame
    SceneDesc s = parse_scene_text(plane_scene(mpu, 14, delta_ns, "constant"), "<scales>", "");
    ASSERT_DOUBLE_EQ(s.meters_per_unit, mpu);
    Rendered r = render(s);
    ASSERT_EQ(r.buffer_non_finite + r.image_non_finite(), 0u);
    FrontCheck f = check_fronts(s, r, 0.01);
    // The front sweeps the plane from 2 to 7 units: most (pixel, frame) pairs are decided.
    EXPECT_GT(f.inside, 2000);
    EXPECT_GT(f.outside, 2000);
    EXPECT_LT(f.straddling, (f.inside + f.outside) / 3);
}

TEST_P(Scales, PulseFramesSumToTheSteadyImage) {
    // Pulse frames of one bucket partition the arrivals: with the timeline covering all of
    // them (up to sqrt(54) units < 7.5), the frames add up to steady.exr at either scale.
    const double mpu = GetParam();
    const double delta_ns = 0.5 * mpu / kSpeedOfLight;
    SceneDesc s = parse_scene_text(plane_scene(mpu, 16, delta_ns, "pulse"), "<scales>", "");
    Rendered r = render(s);
    ASSERT_EQ(r.buffer_non_finite + r.image_non_finite(), 0u);
    double total = 0, steady = 0;
    for (const Image& f : r.frames) total += mean(f);
    steady = mean(r.steady);
    EXPECT_GT(steady, 0.0);
    EXPECT_NEAR(total, steady, 1e-5 * steady);
    // Nothing arrives before the light's height (2 units, frame 4): frames 0-2 are black
    // (frame 3 is left out: float positions may put the nearest point a hair under 2 units).
    for (int k = 0; k < 3; ++k) EXPECT_EQ(mean(r.frames[k]), 0.0) << "frame " << k;
}

INSTANTIATE_TEST_SUITE_P(MillimeterAndTenKilometers, Scales, ::testing::Values(1e-4, 1.0, 1e3),
                         [](const ::testing::TestParamInfo<double>& i) {
                             return i.param < 1e-3 ? std::string("scene_1mm")
                                                   : i.param > 1 ? std::string("scene_10km") : std::string("scene_10m");
                         });

}  // namespace
}  // namespace sl::hard
