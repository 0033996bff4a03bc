// A medium that does nothing renders exactly as vacuum; a dense one (optical depth 20) renders
// finite, plausible values that converge; a pulse through a medium lights the stretch of the
// beam that its frame says (time tags do not drift); results do not depend on thread count.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "render_helpers.h"
#include "stages/render/beam_estimate.h"
#include "scenes_for_tests.h"
#include "test_medium_scenes.h"

namespace sl {
namespace {

SceneDesc hazy_box(Vec3 sigma_a, Vec3 sigma_s, int res, int passes, int photons, int max_depth = 8) {
    SceneDesc s = test::small_box(res, passes, photons, max_depth);
    s.medium.present = true;
    s.medium.sigma_a = sigma_a;
    s.medium.sigma_s = sigma_s;
    return s;  // no bounds: the box itself (the camera is inside it)
}

void expect_identical(const test::Rendered& a, const test::Rendered& b) {
    EXPECT_EQ(a.steady, b.steady);
    ASSERT_EQ(a.frames.size(), b.frames.size());
    for (size_t k = 0; k < a.frames.size(); ++k) EXPECT_EQ(a.frames[k], b.frames[k]) << "frame " << k;
}

TEST(MediumRobust, ZeroExtinctionRendersExactlyAsVacuum) {
    SceneDesc vacuum = test::small_box(16, 3, 4000);
    test::Rendered ref = test::render_all(vacuum);
    SceneDesc s = hazy_box(Vec3(0), Vec3(0), 16, 3, 4000);
    s.medium.g = 0.5f;
    expect_identical(test::render_all(s), ref);
    s.medium.has_bounds = true;
    s.medium.bounds_min = Vec3(-5);
    s.medium.bounds_max = Vec3(5);
    expect_identical(test::render_all(s), ref);
    RenderContext ctx(s);
    EXPECT_FALSE(ctx.medium.has_value());  // nothing volumetric is even set up
}

void expect_finite(const test::Rendered& r, float bound) {
    for (const auto* img : {&r.steady}) {
        for (size_t i = 0; i < img->size(); ++i) {
            ASSERT_TRUE(std::isfinite((*img)[i])) << "pixel " << i / 3;
            ASSERT_GE((*img)[i], 0.0f);
            ASSERT_LE((*img)[i], bound) << "pixel " << i / 3;
        }
    }
    for (const auto& f : r.frames)
        for (float v : f) ASSERT_TRUE(std::isfinite(v));
}

double channel_mean(const std::vector<float>& img, int c) {
    double s = 0;
    for (size_t i = c; i < img.size(); i += 3) s += img[i];
    return s / static_cast<double>(img.size() / 3);
}

// The whole box at optical depth 20 in red and green, clear in blue: red and green go dark,
// blue must stay what it is in vacuum (in expectation: the photons' spectral weights for the
// clear channel are 1 / average transmittance, up to 3, never infinite).
TEST(MediumRobust, DenseBoxWithAClearChannel) {
    SceneDesc s = hazy_box(Vec3(2, 2, 0), Vec3(8, 8, 0), 24, 12, 10000);
    test::Rendered r = test::render_all(s);
    expect_finite(r, 17.0f);  // nothing brighter than the light itself
    SceneDesc v = test::small_box(24, 12, 10000);
    test::Rendered vac = test::render_all(v);
    double blue = channel_mean(r.steady, 2), blue_vac = channel_mean(vac.steady, 2);
    EXPECT_NEAR(blue, blue_vac, 0.05 * blue_vac);
    EXPECT_LT(channel_mean(r.steady, 0), 0.1 * channel_mean(vac.steady, 0));
    EXPECT_LT(channel_mean(r.steady, 1), 0.1 * channel_mean(vac.steady, 1));
}

// A 1 m cube of dense haze (optical depth 20 across it) in the box, in view: it looks like a
// matte object. Finite, no pixel that holds a large share of the image, and two independent
// runs agree, so there is no rare huge contribution that never averages out.
TEST(MediumRobust, DenseCubeIsFiniteAndConverges) {
    SceneDesc s = hazy_box(Vec3(4), Vec3(16), 24, 8, 10000);
    s.medium.has_bounds = true;
    s.medium.bounds_min = {-0.5f, 0.0f, -0.7f};
    s.medium.bounds_max = {0.5f, 1.0f, 0.3f};
    test::Rendered a = test::render_all(s);
    expect_finite(a, 17.0f);
    s.render.seed = 5;
    s.render.passes = 24;
    test::Rendered b = test::render_all(s);
    expect_finite(b, 17.0f);
    test::Rendered v = test::render_all(test::small_box(24, 8, 10000));
    double sum = 0, brightest = 0;
    for (size_t i = 0; i < b.steady.size(); i += 3) {
        double px = b.steady[i] + b.steady[i + 1] + b.steady[i + 2];
        sum += px;
        if (v.steady[i] + v.steady[i + 1] + v.steady[i + 2] < 20) brightest = std::max(brightest, px);  // not the light
    }
    EXPECT_LT(brightest, 0.02 * sum) << "a firefly";
    EXPECT_NEAR(test::mean(a.steady), test::mean(b.steady), 0.05 * test::mean(b.steady));
    double vac = test::mean(v.steady);
    EXPECT_GT(test::mean(b.steady), 0.3 * vac);  // the cube hides part of the room, and glows
    EXPECT_LT(test::mean(b.steady), 1.2 * vac);
}

// A laser along x through a medium, seen from the side: pulse frame k must light only the
// stretch of the beam whose arrival time is in frame k.
void check_pulse(Vec3 sigma_s, bool tof, int lit_frames) {
    LightDesc laser;
    laser.type = LightType::Laser;
    laser.position = {-3, 0, 0};
    laser.direction = {1, 0, 0};
    laser.power = Vec3(1);
    SceneDesc s = test::light_in_open_medium(laser, sigma_s * 0.2f, sigma_s, 0.0f, 4, {0, 0, 4}, {0, 0, 0},
                                             24.68f, 16);
    s.medium.bounds_min = {-4, -1, -1};
    s.medium.bounds_max = {4, 1, 1};
    s.camera.width = 64;
    s.time = {0, 40, 20, 24};  // 2 ns = 0.6 m a frame
    s.emission.mode = EmissionMode::Pulse;
    s.render.passes = 6;
    s.render.photons_per_pass = 20000;
    s.render.radius = 0.03f;
    s.render.camera_tof = tof;
    test::Rendered r = test::render_all(s);
    const double half_w = 3.5;  // x seen at z = 0 spans [-3.5, 3.5]
    // The beam's kernel: the radius, or a pixel footprint at the beam's distance (4 m) if wider.
    const double widen = std::max(0.05, kFootprintRadii * PinholeCamera(s.camera).pixel_footprint(4) + 0.01);
    auto arrival = [&](double x) { return ((x + 3) + (tof ? std::sqrt(x * x + 16) : 0.0)) / test::kC; };
    int checked = 0;
    for (int k = 0; k < s.time.frames; ++k) {
        double t0 = 2.0 * k, t1 = t0 + 2;
        double inside = 0, total = 0;
        for (int i = 0; i < 64; ++i) {
            double xa = (2.0 * i / 64 - 1) * half_w, xb = (2.0 * (i + 1) / 64 - 1) * half_w;
            // The column's beam stretch (widened by the radius) meets the frame's interval?
            bool expected = arrival(xb + widen) >= t0 && arrival(std::max(-3.0, xa - widen)) < t1;
            for (int y = 0; y < 16; ++y)
                for (int c = 0; c < 3; ++c) {
                    double v = r.frames[k][(y * 64 + i) * 3 + c];
                    total += v;
                    if (expected) inside += v;
                }
        }
        if (total > 0) {
            ++checked;
            EXPECT_GT(inside / total, 0.99) << "frame " << k << (tof ? " (tof)" : "");
        }
        // The first frames the pulse crosses must show it.
        int first = static_cast<int>(arrival(-3) / 2);
        if (k >= first && k < first + lit_frames) {
            EXPECT_GT(total, 0) << "frame " << k << (tof ? " (tof)" : "");
        }
    }
    EXPECT_GE(checked, lit_frames);
}

TEST(MediumRobust, PulseArrivesInTheRightFrame) {
    check_pulse(Vec3(0.3f), false, 8);
    check_pulse(Vec3(0.3f), true, 5);
    check_pulse(Vec3(2.0f), false, 3);  // dense: optical depth 2.4 per meter
}

TEST(MediumRobust, SameImageForAnyThreadCount) {
    SceneDesc s = hazy_box(Vec3(0.05f), Vec3(0.4f, 0.3f, 0.2f), 16, 3, 5000);
    s.render.camera_tof = true;
    test::Rendered a, b;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        a = test::render_all(s);
    }
    {
        tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
        b = test::render_all(s);
    }
    expect_identical(a, b);
}

}  // namespace
}  // namespace sl
