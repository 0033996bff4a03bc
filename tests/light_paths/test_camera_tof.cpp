// Camera time of flight (issue 6): with render.camera_tof, a pulse's arrival at a pixel is later
// by exactly (distance from the seen point to the camera) / c, to within a bucket.
//
// Method: a point light over a plane, direct light only (max_depth 1), pulse emission of one
// bucket. A pixel's arrival frame is the first pulse frame in which it holds any light. The same
// seed gives the same jittered pixel samples with and without camera_tof, so the per-pixel shift
// of the first frame is the camera distance of the earliest sample, quantised: it must equal
// round(|x - camera| / c / delta) +- 1 wherever the camera distance varies by less than half a
// bucket across the pixel (see the bound in `shift_tolerance_holds`). The absolute arrival frame
// is also checked against the light-to-point (+ point-to-camera) length over the pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "light_paths_helpers.h"

namespace sl {
namespace {

using lp::kC;

// The min and max over a pixel (sampled on an n x n grid including its edges) of f(point),
// where the point is where the camera ray meets the plane dot(n, x) = offset.
template <class F>
void pixel_range(const PinholeCamera& cam, int px, int py, Vec3 n, float offset, F f, double& lo, double& hi,
                 int grid = 5) {
    lo = 1e300;
    hi = -1e300;
    for (int i = 0; i < grid; ++i)
        for (int j = 0; j < grid; ++j) {
            float fx = px + float(i) / (grid - 1), fy = py + float(j) / (grid - 1);
            double v = f(lp::on_plane(cam, fx, fy, n, offset));
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
}

struct TofCheck {
    int checked_shift = 0, checked_abs = 0;
    int bad_shift = 0, bad_abs = 0;
    double max_abs_shift_err = 0;  // |measured shift - expected shift| in buckets
};

// Renders `s` with and without camera_tof and checks every pixel that sees the plane
// dot(n, x) = offset (lit by point light `light`).
TofCheck check_tof(SceneDesc s, Vec3 n, float offset, Vec3 light, std::vector<int>* first_no = nullptr,
                   std::vector<int>* first_tof = nullptr) {
    const double delta = timeline_of(s).delta();
    s.render.camera_tof = false;
    lp::Rendered no = lp::render_all(s);
    s.render.camera_tof = true;
    lp::Rendered yes = lp::render_all(s);
    PinholeCamera cam(s.camera);
    const Vec3 cp = cam.position();
    TofCheck out;
    const int W = s.camera.width, H = s.camera.height;
    if (first_no) first_no->assign(size_t(W) * H, -1);
    if (first_tof) first_tof->assign(size_t(W) * H, -1);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            lp::Arrival a0 = lp::arrival(no, x, y), a1 = lp::arrival(yes, x, y);
            if (first_no) (*first_no)[size_t(y) * W + x] = a0.first;
            if (first_tof) (*first_tof)[size_t(y) * W + x] = a1.first;
            if (a0.first < 0 || a1.first < 0) {
                ADD_FAILURE() << "pixel " << x << "," << y << " never lit";
                continue;
            }
            // Absolute arrival: the earliest sample lies in the pixel, so the first frame lies
            // between the buckets of the pixel's shortest and longest path (one bucket of slack
            // for the grid's resolution).
            double l_lo, l_hi, t_lo, t_hi, b_lo, b_hi;
            pixel_range(cam, x, y, n, offset, [&](Vec3 p) { return length(p - light) / kC; }, l_lo, l_hi);
            pixel_range(cam, x, y, n, offset, [&](Vec3 p) { return (length(p - light) + length(p - cp)) / kC; },
                        t_lo, t_hi);
            pixel_range(cam, x, y, n, offset, [&](Vec3 p) { return length(p - cp) / kC; }, b_lo, b_hi);
            ++out.checked_abs;
            bool ok0 = a0.first >= lp::bucket_of(l_lo, delta) - 1 && a0.first <= lp::bucket_of(l_hi, delta);
            bool ok1 = a1.first >= lp::bucket_of(t_lo, delta) - 1 && a1.first <= lp::bucket_of(t_hi, delta);
            if (!ok0 || !ok1) {
                if (++out.bad_abs <= 5)
                    ADD_FAILURE() << "pixel " << x << "," << y << ": first frame " << a0.first << " / tof "
                                  << a1.first << ", expected [" << lp::bucket_of(l_lo, delta) - 1 << ","
                                  << lp::bucket_of(l_hi, delta) << "] / [" << lp::bucket_of(t_lo, delta) - 1
                                  << "," << lp::bucket_of(t_hi, delta) << "]";
            }
            // The shift: exact to a bucket where the camera distance b varies by e < delta/2 over
            // the pixel. In buckets, shift = floor(A + b_s) - floor(A) for the earliest sample s,
            // so b_min - 1 < shift < b_max + 1, and |shift - round(b_centre)| < 3/2 + e < 2.
            if (b_hi - b_lo < 0.5 * delta) {
                Vec3 pc = lp::on_plane(cam, x + 0.5f, y + 0.5f, n, offset);
                int expected = static_cast<int>(std::lround(length(pc - cp) / kC / delta));
                int shift = a1.first - a0.first;
                ++out.checked_shift;
                out.max_abs_shift_err = std::max(out.max_abs_shift_err, double(std::abs(shift - expected)));
                if (std::abs(shift - expected) > 1 && ++out.bad_shift <= 5)
                    ADD_FAILURE() << "pixel " << x << "," << y << ": tof shift " << shift << " buckets, expected "
                                  << expected;
            }
        }
    return out;
}

// A plane facing the camera at distance D = 3 m, a point light 1 m in front of it.
TEST(CameraTof, FrontalPlaneArrivalIsLaterByDistanceToCamera) {
    constexpr float D = 3.0f;
    constexpr int kRes = 48;
    SceneDesc s = lp::empty_scene({0, 0, D}, {0, 0, 0}, {0, 1, 0}, 30, kRes);
    int grey = lp::add_material(s, MaterialType::Diffuse, Vec3(0.5f));
    lp::add_quad(s, {-5, -5, 0}, {10, 0, 0}, {0, 10, 0}, grey);
    const Vec3 light{0.2f, 0.1f, 1.0f};
    lp::add_point_light(s, light, 100);
    s.time = {0, 20, 200, 24};  // delta = 0.1 ns = 3 cm of light; the tof shift is ~100 buckets
    s.render.passes = 4;
    s.render.photons_per_pass = 100;  // max_depth 1: no photon is ever stored
    std::vector<int> f0, f1;
    TofCheck c = check_tof(s, {0, 0, 1}, 0, light, &f0, &f1);
    EXPECT_EQ(c.checked_abs, kRes * kRes);
    EXPECT_GT(c.checked_shift, kRes * kRes * 9 / 10);  // the others vary by >= delta/2 over the pixel
    EXPECT_EQ(c.bad_abs, 0);
    EXPECT_EQ(c.bad_shift, 0);
    // The centre pixel: the shift is D / c = 10.007 ns = 100 buckets.
    const size_t mid = size_t(kRes / 2) * kRes + kRes / 2;
    EXPECT_NEAR(f1[mid] - f0[mid], 100, 1);
    RecordProperty("centre_shift_buckets", f1[mid] - f0[mid]);
    std::printf("[frontal plane] centre pixel: first frame %d without tof, %d with (shift %d, expected %.2f); "
                "max |shift error| %.0f bucket over %d pixels\n",
                f0[mid], f1[mid], f1[mid] - f0[mid], D / kC / 0.1, c.max_abs_shift_err, c.checked_shift);
}

// A plane tilted 50 degrees about the vertical: its left part is near the camera, its right part
// far. The light sits on the plane's normal through its centre, so without tof points at equal
// distance from the centre light up together; with tof the far part lights up later.
TEST(CameraTof, FarPartOfTiltedPlaneLightsUpLater) {
    constexpr int kRes = 64;  // 20 degrees over 64 pixels: a pixel's camera distance varies < delta/2
    SceneDesc s = lp::empty_scene({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 20, kRes);
    int grey = lp::add_material(s, MaterialType::Diffuse, Vec3(0.5f));
    const float th = 50 * kPi / 180;
    const Vec3 u{std::cos(th), 0, -std::sin(th)}, v{0, 1, 0};
    const Vec3 n = cross(u, v);  // (sin, 0, cos): towards the camera's side
    lp::add_quad(s, u * -5.0f + v * -5.0f, u * 10.0f, v * 10.0f, grey);
    const Vec3 light = n * 1.0f;
    lp::add_point_light(s, light, 100);
    s.time = {0, 30, 150, 24};  // delta = 0.2 ns
    s.render.passes = 4;
    s.render.photons_per_pass = 100;
    std::vector<int> f0, f1;
    TofCheck c = check_tof(s, n, 0, light, &f0, &f1);
    EXPECT_EQ(c.checked_abs, kRes * kRes);
    EXPECT_GT(c.checked_shift, kRes * kRes * 7 / 10);  // the others vary by >= delta/2 over the pixel
    EXPECT_EQ(c.bad_abs, 0);
    EXPECT_EQ(c.bad_shift, 0);

    // Along the middle row: a near pixel and the far pixel at the same distance from the light.
    PinholeCamera cam(s.camera);
    const int row = kRes / 2;
    const int near_x = 3;
    Vec3 pn = lp::on_plane(cam, near_x + 0.5f, row + 0.5f, n, 0);
    int far_x = -1;
    double best = 1e9;
    for (int x = kRes / 2; x < kRes; ++x) {
        Vec3 p = lp::on_plane(cam, x + 0.5f, row + 0.5f, n, 0);
        double diff = std::abs(length(p - light) - length(pn - light));
        if (diff < best) best = diff, far_x = x;
    }
    ASSERT_GE(far_x, 0);
    Vec3 pf = lp::on_plane(cam, far_x + 0.5f, row + 0.5f, n, 0);
    const double delta = timeline_of(s).delta();
    const double extra = (length(pf - cam.position()) - length(pn - cam.position())) / kC / delta;
    const size_t in = size_t(row) * kRes + near_x, ifar = size_t(row) * kRes + far_x;
    EXPECT_LE(std::abs(f0[ifar] - f0[in]), 1) << "without tof, equal light paths arrive together";
    EXPECT_GT(extra, 10) << "geometry: the far point must be much farther from the camera";
    EXPECT_NEAR(f1[ifar] - f1[in], extra, 2.0) << "with tof, the far point is later by its extra camera distance";
    EXPECT_GT(f1[ifar] - f1[in], 10);
    // And the far half as a whole lights up later than the near half, only with tof.
    double mean_no[2] = {0, 0}, mean_tof[2] = {0, 0};
    for (int y = 0; y < kRes; ++y)
        for (int x = 0; x < kRes; ++x) {
            int half = x < kRes / 2 ? 0 : 1;
            mean_no[half] += f0[size_t(y) * kRes + x];
            mean_tof[half] += f1[size_t(y) * kRes + x];
        }
    const double per_half = kRes * kRes / 2.0;
    EXPECT_GT((mean_tof[1] - mean_tof[0]) / per_half, (mean_no[1] - mean_no[0]) / per_half + 5);
    std::printf("[tilted plane] shift checked on %d pixels (max error %.0f bucket), absolute arrival on %d\n",
                c.checked_shift, c.max_abs_shift_err, c.checked_abs);
    std::printf("[tilted plane] near pixel %d / far pixel %d (row %d): first frames %d / %d without tof, %d / %d "
                "with tof; far-near extra camera delay %.2f buckets, measured %d\n",
                near_x, far_x, row, f0[in], f0[ifar], f1[in], f1[ifar], extra, (f1[ifar] - f1[in]) - (f0[ifar] - f0[in]));
}

}  // namespace
}  // namespace sl
