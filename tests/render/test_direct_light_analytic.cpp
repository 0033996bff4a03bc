// A point light over a large diffuse plane, direct light only (max_depth 1): the rendered
// radiance must match rho/pi * I cos(theta) / r^2, and in constant emission the lit region of
// frame k must be the disk where the light-to-point distance is below c * t_(k+1). And a quad
// lamp low over a floor against the closed form of a parallel rectangle's irradiance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

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

// A quad lamp low over a floor, facing it (parallel planes h apart), seen from 3 m up beside
// it: each pixel's radiance against the closed form of the irradiance from a parallel
// rectangle (the configuration factor of a point to a rectangle above a corner, summed over the
// four corners). The shadow ray toward a point of the lamp starts lifted off the floor; when its
// length was measured from the unlifted point, the lamp's own surface blocked it for every h
// below about 0.2 m: the floor was black.
double parallel_corner(double a, double b, double h) {  // signed: a rectangle [0, a] x [0, b] at height h
    const double s = (a < 0) != (b < 0) ? -1.0 : 1.0;
    const double A = std::abs(a) / h, B = std::abs(b) / h;
    return s * (A / std::sqrt(1 + A * A) * std::atan(B / std::sqrt(1 + A * A)) +
                B / std::sqrt(1 + B * B) * std::atan(A / std::sqrt(1 + B * B))) / (2 * sl::kPiDouble);
}

TEST(DirectLightAnalytic, AFloorUnderALowLampGetsItsLight) {
    for (const float h : {0.05f, 0.15f}) {
        SCOPED_TRACE(h);
        const int res = 24;
        const float L = 5, rho = 0.6f, x0 = -0.3f, x1 = 0.3f, z0 = -0.25f, z1 = 0.25f;
        SceneDesc s = test::looking_down_at_grey("<low lamp>", res, 0.6f, rho);
        s.camera.position = {1.0f, 3, 0};  // the floor from x = 0.4 to 1.6 m: beside the lamp
        s.camera.look_at = {1.0f, 0, 0};
        s.shapes.push_back(test::quad({-3, 0, 3}, {6, 0, 0}, {0, 0, -6}));
        // edge1 x edge2 faces down, onto the floor
        s.lights.push_back(test::quad_light({x0, h, z0}, {x1 - x0, 0, 0}, {0, 0, z1 - z0}, L));
        s.render.max_depth = 1;
        s.render.passes = 128;
        s.render.photons_per_pass = 1000;
        const test::Rendered r = test::render_all(s);
        const PinholeCamera cam(s.camera);
        double got_sum = 0, want_sum = 0;
        std::vector<double> ratios;
        for (int py = 0; py < res; ++py)
            for (int px = 0; px < res; ++px) {
                const int n = 32;
                double want = 0;
                for (int i = 0; i < n; ++i)
                    for (int j = 0; j < n; ++j) {
                        const Vec3 x = on_plane(cam, px + (i + 0.5f) / n, py + (j + 0.5f) / n);
                        const double F = parallel_corner(x1 - x.x, z1 - x.z, h) - parallel_corner(x0 - x.x, z1 - x.z, h) -
                                         parallel_corner(x1 - x.x, z0 - x.z, h) + parallel_corner(x0 - x.x, z0 - x.z, h);
                        want += rho * L * F / (n * n);  // rho / pi * (pi L F)
                    }
                const double got = r.steady[(py * res + px) * 3];
                got_sum += got;
                want_sum += want;
                ratios.push_back(got / want);
            }
        // The pixels nearest the lamp see it at grazing angles, where one point of its area a pass
        // leaves a long tail (a few of them off by up to 23 % at 128 passes): the image's sum and
        // its median pixel are checked (measured: +1.4 % and +0.03 % at h = 0.05 m, +0.6 % and
        // +0.03 % at 0.15 m), and no pixel may be dark (before the fix: all of them, 0).
        std::sort(ratios.begin(), ratios.end());
        EXPECT_NEAR(got_sum, want_sum, 0.03 * want_sum);
        EXPECT_NEAR(ratios[ratios.size() / 2], 1.0, 0.01);
        EXPECT_GT(ratios.front(), 0.5);
    }
}

}  // namespace
}  // namespace sl
