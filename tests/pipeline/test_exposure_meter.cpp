// The exposure's two ingredients checked against numbers derived by hand: which pixels see a lamp
// (against the lamp's outline projected through the camera), and the statistics made from the
// rest (mean, percentile, follow) on images whose answers are known.
#include <gtest/gtest.h>

#include <cmath>

#include "foundation/constants.h"
#include "config/parse_scene.h"
#include "pipeline/exposure.h"
#include "stages/render/render_context.h"
#include "tests/test_paths.h"

using namespace sl;

namespace {

struct Projected {
    double x, y;
};

// The camera's own projection, written out: pixel coordinates of a world point.
Projected project(const CameraDesc& c, Vec3 p) {
    const Vec3 f = normalize(c.look_at - c.position), r = normalize(cross(f, c.up)), u = cross(r, f);
    const Vec3 d = p - c.position;
    const double half_h = std::tan(c.vfov_deg * sl::kPiDouble / 360.0), half_w = half_h * c.width / c.height;
    const double z = dot(d, f);
    return {(dot(d, r) / z / half_w + 1) * c.width / 2, (1 - dot(d, u) / z / half_h) * c.height / 2};
}

}  // namespace

TEST(EmitterPixels, AreTheLampsProjectedOutlineAndItsEdgePixels) {
    SceneDesc s = parse_scene_file(std::string(test::source_dir()) + "/samples/cornell_box.json");
    s.camera.width = s.camera.height = 128;
    RenderContext ctx(s);
    const std::vector<uint8_t> mask = emitter_pixels(ctx);
    const LightDesc& lamp = s.lights[0];
    const Projected q[4] = {project(s.camera, lamp.corner), project(s.camera, lamp.corner + lamp.edge1),
                            project(s.camera, lamp.corner + lamp.edge1 + lamp.edge2),
                            project(s.camera, lamp.corner + lamp.edge2)};
    double area = 0, perimeter = 0;
    for (int i = 0; i < 4; ++i) {
        const Projected a = q[i], b = q[(i + 1) % 4];
        area += 0.5 * (a.x * b.y - b.x * a.y);
        perimeter += std::hypot(b.x - a.x, b.y - a.y);
    }
    area = std::abs(area);
    size_t count = 0;
    for (uint8_t m : mask) count += m;
    ASSERT_GT(area, 10) << "the lamp should cover some pixels";
    // Every pixel the outline covers, plus at most the pixels its edge crosses.
    EXPECT_GE(static_cast<double>(count), area);
    EXPECT_LE(static_cast<double>(count), area + perimeter + 4);
}

TEST(ExposureMeter, MeanLeavesTheLampOut) {
    const size_t n = 1000;
    std::vector<float> rgb(3 * n, 0.5f);
    std::vector<uint8_t> mask(n, 0);
    for (size_t p = 0; p < 10; ++p) {  // a lamp 1000 times brighter on 1 % of the pixels
        mask[p] = 1;
        rgb[3 * p] = rgb[3 * p + 1] = rgb[3 * p + 2] = 500.0f;
    }
    ExposureMeter meter(EmissionMode::Constant, {}, mask);
    meter.add_steady(rgb.data(), n);
    ExposurePlan plan = meter.decide();
    EXPECT_NEAR(plan.reference, 0.5, 1e-6);
    EXPECT_NEAR(plan.base, kConstantKey / 0.5, 1e-6);
    EXPECT_FALSE(plan.black);

    ExposureMeter dark(EmissionMode::Constant, {}, mask);
    std::vector<float> black(3 * n, 0.0f);
    for (size_t p = 0; p < 10; ++p) black[3 * p] = 500.0f;
    dark.add_steady(black.data(), n);
    EXPECT_TRUE(dark.decide().black) << "only the lamp is lit";
}

TEST(ExposureMeter, PercentileAndPulseBrightestFrame) {
    const size_t n = 1000;
    std::vector<float> rgb(3 * n);
    for (size_t p = 0; p < n; ++p) rgb[3 * p] = rgb[3 * p + 1] = rgb[3 * p + 2] = static_cast<float>(p + 1);  // 1..1000
    ExposureRule rule;
    rule.percentile = 90;
    ExposureMeter meter(EmissionMode::Constant, rule, {});
    meter.add_steady(rgb.data(), n);
    EXPECT_NEAR(meter.decide().base, 1.0 / 900.0, 1e-9);  // the 900th of 1..1000 to white

    // Pulses: the brightest frame's mean.
    ExposureMeter pulse(EmissionMode::Pulse, {}, {});
    for (int k = 0; k < 5; ++k) {
        std::vector<float> f(3 * n, k == 2 ? 2.0f : 0.25f);
        pulse.add_frame(k, f.data(), n);
    }
    EXPECT_NEAR(pulse.decide().base, kPulseKey / 2.0, 1e-9);
}

TEST(ExposureMeter, FollowRisesSmoothlyAfterThePeakOnly) {
    const size_t n = 16;
    ExposureRule rule;
    rule.follow = true;
    ExposureMeter meter(EmissionMode::Pulse, rule, {});
    const int frames = 40;
    for (int k = 0; k < frames; ++k) {
        // Dark until frame 5, a peak at 5, then a tenfold fade every 10 frames.
        const float level = k < 5 ? 0.0f : static_cast<float>(std::pow(10.0, -(k - 5) / 10.0));
        std::vector<float> f(3 * n, level);
        meter.add_frame(k, f.data(), n);
    }
    ExposurePlan plan = meter.decide();
    ASSERT_EQ(plan.per_frame.size(), static_cast<size_t>(frames));
    for (int k = 0; k <= 5; ++k) EXPECT_DOUBLE_EQ(plan.per_frame[k], plan.base) << k;
    for (int k = 6; k < frames; ++k) {
        EXPECT_GE(plan.per_frame[k], plan.per_frame[k - 1] * (1 - 1e-12)) << k;
        EXPECT_LT(plan.per_frame[k] / plan.per_frame[k - 1], 1.27) << k;  // a 10x fade over 10 frames: 1.259 a frame
    }
    // Well inside the fade the average trails the fade by (1 - 1/3) / (1/3) = 2 frames: the frames
    // show 10^(-2/10) = 0.63 of the peak's brightness, steadily.
    for (int k : {15, 20, 25}) {
        const double shown = plan.per_frame[k] * std::pow(10.0, -(k - 5) / 10.0) / plan.base;
        EXPECT_NEAR(shown, std::pow(10.0, -0.2), 0.02) << k << " gain " << plan.per_frame[k] / plan.base;
    }
    // Past 256 times the fixed exposure it stops rising (the last frames are 10^-3.4 of the peak).
    EXPECT_LE(plan.per_frame.back(), kFollowMaxGain * plan.base * (1 + 1e-12));
    EXPECT_GT(plan.per_frame.back(), 0.9 * kFollowMaxGain * plan.base);
}
