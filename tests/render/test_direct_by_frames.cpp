// A flash from a quad light over a floor, direct light only (max_depth 1), frames of 0.2 ns
// (6 cm of light) so that the lamp's light reaches each floor point over several frames: the
// direct light sampled frame by frame (direct_by_frames.h) must give each frame's image mean of a
// quadrature of the lamp's irradiance by distance, and far less per-pixel noise than one sample
// of the whole lamp per pass.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "foundation/constants.h"
#include "render_helpers.h"
#include "scenes_for_tests.h"

namespace sl {
namespace {

constexpr int kRes = 24, kFrames = 40;
constexpr float kRho = 0.6f, kRadiance = 5.0f;
const Vec3 kCorner(-0.3f, 0.5f, -0.25f), kE1(0.6f, 0, 0), kE2(0, 0, 0.5f);  // front faces down

// The camera 3 m up looks straight down at the floor beside the lamp (x from 0.4 to 1.6 m), so
// that no camera ray meets the lamp.
SceneDesc flash_over_floor(int passes, uint64_t seed) {
    SceneDesc s = test::looking_down_at_grey("<flash over a floor>", kRes, 0.6f, kRho);
    s.camera.position = {1.0f, 3, 0};
    s.camera.look_at = {1.0f, 0, 0};
    s.shapes.push_back(test::quad({-3, 0, 3}, {6, 0, 0}, {0, 0, -6}));
    s.lights.push_back(test::quad_light(kCorner, kE1, kE2, kRadiance));
    s.time = {0, 0.2 * kFrames, kFrames, 24};
    s.emission.mode = EmissionMode::Pulse;
    s.render.max_depth = 1;
    s.render.passes = passes;
    s.render.photons_per_pass = 1000;
    s.render.seed = seed;
    return s;
}

// Each frame's image mean by quadrature: 4 x 4 points of each pixel on the floor, each lit by
// 120 x 120 points of the lamp, every one's light in the frame of its distance over c.
std::vector<double> quadrature_means(const SceneDesc& s) {
    const PinholeCamera cam(s.camera);
    std::vector<double> mean(kFrames, 0.0);
    const int sub = 4, n = 120;
    const double cell = 0.6 * 0.5 / (double(n) * n), c = kSpeedOfLight;
    for (int py = 0; py < kRes; ++py)
        for (int px = 0; px < kRes; ++px)
            for (int a = 0; a < sub; ++a)
                for (int b = 0; b < sub; ++b) {
                    const Vec3 d = cam.direction(px + (a + 0.5f) / sub, py + (b + 0.5f) / sub);
                    const Vec3 x = cam.position() + d * (-cam.position().y / d.y);
                    for (int i = 0; i < n; ++i)
                        for (int j = 0; j < n; ++j) {
                            const Vec3 y = kCorner + kE1 * ((i + 0.5f) / n) + kE2 * ((j + 0.5f) / n);
                            const Vec3 v = y - x;
                            const double d2 = dot(v, v), dist = std::sqrt(d2);
                            const double cos2 = (v.y / dist) * (v.y / dist);  // both cosines: v.y / dist
                            const int k = static_cast<int>(std::floor(dist / c / 0.2));
                            if (k >= 0 && k < kFrames) mean[k] += kRho / kPiDouble * kRadiance * cos2 / d2 * cell;
                        }
                }
    for (double& m : mean) m /= double(kRes) * kRes * sub * sub;
    return mean;
}

double frame_mean(const std::vector<float>& f) { return test::mean(f); }

// The median over frames brighter than 5 % of the brightest of the per-pixel noise: the RMS of
// the two seeds' difference over sqrt 2, relative to the frame's mean.
double median_noise(const test::Rendered& a, const test::Rendered& b) {
    double brightest = 0;
    for (const auto& f : a.frames) brightest = std::max(brightest, frame_mean(f));
    std::vector<double> noise;
    for (size_t k = 0; k < a.frames.size(); ++k) {
        const double m = 0.5 * (frame_mean(a.frames[k]) + frame_mean(b.frames[k]));
        if (!(m > 0.05 * brightest)) continue;
        noise.push_back(test::rmse(a.frames[k], b.frames[k]) / std::sqrt(2.0) / m);
    }
    std::sort(noise.begin(), noise.end());
    return noise.empty() ? 0.0 : noise[noise.size() / 2];
}

TEST(DirectByFrames, EachFramesMeanIsTheQuadratureOfTheLampByDistance) {
    const SceneDesc s = flash_over_floor(32, 1);
    const std::vector<double> want = quadrature_means(s);
    const test::Rendered r = test::render_all(s);
    ASSERT_EQ(r.frames.size(), size_t(kFrames));
    double brightest = 0, total = 0, got_total = 0;
    for (double m : want) brightest = std::max(brightest, m);
    int checked = 0;
    for (int k = 0; k < kFrames; ++k) {
        const double got = frame_mean(r.frames[k]);
        total += want[k];
        got_total += got;
        if (want[k] == 0) {
            EXPECT_EQ(got, 0.0) << "frame " << k << ": light before it can arrive";
            continue;
        }
        if (want[k] < 0.05 * brightest) continue;
        EXPECT_NEAR(got, want[k], 0.02 * want[k]) << "frame " << k;
        ++checked;
    }
    EXPECT_GE(checked, 6);  // the lamp's light spreads over many frames: the test means something
    EXPECT_NEAR(got_total, total, 0.005 * total);
}

TEST(DirectByFrames, FramesAreSmootherThanOneSampleOfTheWholeLamp) {
    auto render = [](uint64_t seed, bool by_frames) {
        return test::render_switched(flash_over_floor(16, seed),
                                     [&](RenderContext& ctx) { ctx.pulse_direct_by_frames = by_frames; });
    };
    const double banded = median_noise(render(1, true), render(2, true));
    const double whole = median_noise(render(1, false), render(2, false));
    // Measured: 2.9 % against 78 % (one sample of the lamp per pass, landing in one frame).
    EXPECT_LT(banded * 5, whole) << banded << " vs " << whole;
    EXPECT_GT(banded, 0.0);
}

TEST(DirectByFrames, OneSampleOfTheWholeLampGivesTheSameFramesOnAverage) {
    // The second path through the code: the frame means of one sample per pass, at 16x the passes.
    const test::Rendered banded = test::render_all(flash_over_floor(32, 3));
    const test::Rendered whole = test::render_switched(
        flash_over_floor(512, 4), [](RenderContext& ctx) { ctx.pulse_direct_by_frames = false; });
    double brightest = 0;
    for (const auto& f : whole.frames) brightest = std::max(brightest, frame_mean(f));
    for (int k = 0; k < kFrames; ++k) {
        const double a = frame_mean(banded.frames[k]), b = frame_mean(whole.frames[k]);
        if (b < 0.05 * brightest) continue;
        EXPECT_NEAR(a, b, 0.025 * b) << "frame " << k;  // measured: within 1.1 %
    }
}

TEST(DirectByFrames, ALampOnTheFloorStaysFinite) {
    // The lamp 1 mm over the floor, its edges at the pixels' points (d -> 0, grazing cosines),
    // frames of 0.05 ns: every value finite and non-negative, and light in the frames.
    SceneDesc s = flash_over_floor(16, 1);
    s.lights[0].corner = Vec3(0.5f, 0.001f, -0.25f);  // under the camera's view
    s.time = {0, 0.05 * kFrames, kFrames, 24};
    const test::Rendered r = test::render_all(s);
    double total = 0;
    for (int k = 0; k < kFrames; ++k) {
        for (float v : r.frames[k]) ASSERT_TRUE(std::isfinite(v) && v >= 0) << "frame " << k;
        total += frame_mean(r.frames[k]);
    }
    EXPECT_GT(total, 0.0);
}

TEST(DirectByFrames, AFlashSpreadOverMoreThanItsBandsIsTheOneSample) {
    // Frames of 2 ps: the lamp's light reaches each floor point over 1.2 ns or more, far more
    // than kMaxFrameBands frames, so it is one sample of the whole lamp, exactly as with the
    // switch off.
    auto scene = [] {
        SceneDesc s = flash_over_floor(8, 1);
        s.time = {3.0, 3.0 + 2e-3 * kFrames, kFrames, 24};
        return s;
    };
    const test::Rendered on = test::render_all(scene());
    const test::Rendered off = test::render_switched(scene(), [](RenderContext& ctx) { ctx.pulse_direct_by_frames = false; });
    double lit = 0;
    for (int k = 0; k < kFrames; ++k) {
        EXPECT_EQ(on.frames[k], off.frames[k]) << "frame " << k;
        lit += frame_mean(on.frames[k]);
    }
    EXPECT_GT(lit, 0.0);  // some light arrives in these 80 ps
}

}  // namespace
}  // namespace sl
