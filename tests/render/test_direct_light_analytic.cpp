// A point light over a large diffuse plane, direct light only (max_depth 1): the rendered
// radiance must match rho/pi * I cos(theta) / r^2, and in constant emission the lit region of
// frame k must be the disk where the light-to-point distance is below c * t_(k+1).
#include <gtest/gtest.h>

#include <cmath>

#include "foundation/constants.h"
#include "render_helpers.h"
#include "scenes_for_tests.h"

namespace sl {
namespace {

constexpr float kRho = 0.5f, kPower = 100.0f, kLightH = 1.0f, kCamH = 3.0f;
constexpr int kRes = 48;

// Where the camera ray through image point (fx, fy) meets the plane y = 0.
Vec3 on_plane(const PinholeCamera& cam, float fx, float fy) {
    Vec3 d = cam.direction(fx, fy);
    float t = -cam.position().y / d.y;
    return cam.position() + d * t;
}

double expected_radiance(const PinholeCamera& cam, int px, int py) {
    const double I = kPower / (4 * sl::kPiDouble);
    const int n = 8;  // the pixel average, by a midpoint rule over n x n points
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            Vec3 x = on_plane(cam, px + (i + 0.5f) / n, py + (j + 0.5f) / n);
            double r2 = x.x * x.x + x.z * x.z + kLightH * kLightH, r = std::sqrt(r2);
            sum += kRho / sl::kPiDouble * I * (kLightH / r) / r2;
        }
    return sum / (n * n);
}

TEST(DirectLightAnalytic, RadianceMatchesInverseSquareCosineLaw) {
    SceneDesc s = test::plane_under_point_light(kRho, kPower, kLightH, kCamH, kRes);
    s.render.passes = 64;
    test::Rendered r = test::render_all(s);
    PinholeCamera cam(s.camera);
    double worst = 0, total_err = 0, total = 0, signed_err = 0;
    for (int y = 0; y < kRes; ++y)
        for (int x = 0; x < kRes; ++x) {
            double want = expected_radiance(cam, x, y);
            for (int c = 0; c < 3; ++c) {
                double got = r.steady[(y * kRes + x) * 3 + c];
                worst = std::max(worst, std::abs(got - want) / want);
                total_err += std::abs(got - want);
                signed_err += got - want;
                total += want;
            }
        }
    // Per pixel only the jittered pixel samples are random: a few percent at most.
    EXPECT_LT(std::abs(signed_err) / total, 0.002) << "bias";
    EXPECT_LT(worst, 0.03);
    EXPECT_LT(total_err / total, 0.005);
}

TEST(DirectLightAnalytic, LitRegionOfFrameKIsTheDiskReachedByLight) {
    SceneDesc s = test::plane_under_point_light(kRho, kPower, kLightH, kCamH, kRes);
    s.time = {0, 10, 10, 24};  // 1 ns = 0.2998 m per frame
    test::Rendered r = test::render_all(s);
    PinholeCamera cam(s.camera);
    const double c = 0.299792458;
    int inside_checked = 0, outside_checked = 0;
    for (int k = 0; k < s.time.frames; ++k) {
        const double reach = c * (k + 1);  // light-to-point distance reached by frame k's end
        for (int y = 0; y < kRes; ++y)
            for (int x = 0; x < kRes; ++x) {
                double dmin = 1e9, dmax = 0;
                for (int cy = 0; cy <= 1; ++cy)
                    for (int cx = 0; cx <= 1; ++cx) {
                        Vec3 p = on_plane(cam, float(x + cx), float(y + cy));
                        double d = std::sqrt(p.x * p.x + p.z * p.z + kLightH * kLightH);
                        dmin = std::min(dmin, d);
                        dmax = std::max(dmax, d);
                    }
                Vec3 a = on_plane(cam, float(x), float(y)), b = on_plane(cam, float(x + 1), float(y + 1));
                dmin -= length(a - b);  // the nearest point may lie inside the pixel
                const float* got = &r.frames[k][(y * kRes + x) * 3];
                const float* steady = &r.steady[(y * kRes + x) * 3];
                if (dmax < reach) {
                    ++inside_checked;
                    EXPECT_NEAR(got[0], steady[0], 1e-5 * steady[0]) << "frame " << k << " pixel " << x << "," << y;
                } else if (dmin >= reach) {
                    ++outside_checked;
                    EXPECT_EQ(got[0], 0.0f) << "frame " << k << " pixel " << x << "," << y;
                }
            }
    }
    EXPECT_GT(inside_checked, 1000);
    EXPECT_GT(outside_checked, 1000);
    // The first frames end before light can reach the plane at all (distance >= 1 m).
    EXPECT_EQ(test::mean(r.frames[0]), 0.0);
    EXPECT_EQ(test::mean(r.frames[2]), 0.0);
    EXPECT_GT(test::mean(r.frames[3]), 0.0);
}

}  // namespace
}  // namespace sl
