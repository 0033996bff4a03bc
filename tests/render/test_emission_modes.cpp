// One convergence gives both videos: pulse frames (w = delta) sum to the last constant frame
// minus what arrived before start, and the last constant frame equals steady.exr once end_ns
// is past every path's length.
#include <gtest/gtest.h>

#include "render_helpers.h"
#include "stages/render/frame_assembly.h"
#include "scenes_for_tests.h"

namespace sl {
namespace {

TEST(EmissionModes, PulseFramesSumToLastConstantFrameMinusBeforeStart) {
    SceneDesc s = test::small_box(16, 4, 4000, 4);
    s.time = {5, 17, 12, 24};  // starts after light has already reached the walls
    RenderContext ctx(s);
    std::vector<float> last, frame, sum(ctx.pixels() * 3, 0.0f);
    std::vector<float> slot0;  // what arrived before start, per pixel and channel, over the passes
    FramesInMemory sink;
    sink.on_section_rendered = [&](int, const SectionBuffer& buffer) {  // the one section, assembled both ways
        FrameAssembler constant(buffer, EmissionMode::Constant, 1), pulse(buffer, EmissionMode::Pulse, 1);
        for (int k = 0; k < s.time.frames; ++k) {
            constant.frame(k, last);
            pulse.frame(k, frame);
            for (size_t i = 0; i < sum.size(); ++i) sum[i] += frame[i];
        }
        for (size_t i = 0; i < sum.size(); ++i) slot0.push_back(buffer.slot(i / 3, 0)[i % 3] / float(buffer.passes_done));
    };
    render_frames(ctx, {}, sink);
    ASSERT_EQ(slot0.size(), sum.size());
    double before = 0, total_sum = 0, total_last = 0;
    for (float v : slot0) before += v;
    for (size_t i = 0; i < sum.size(); ++i) {
        EXPECT_NEAR(sum[i], last[i] - slot0[i], 1e-4 * (1 + last[i]));
        total_sum += sum[i];
        total_last += last[i];
    }
    EXPECT_GT(before, 0.01 * total_last);  // the test means something: light arrived before start
    EXPECT_GT(total_sum, 0.0);
}

TEST(EmissionModes, LastConstantFrameEqualsSteadyWhenAllLightHasArrived) {
    // max_depth 3 in a 2 m box: no path is longer than 4 x 3.47 m = 46 ns of light.
    SceneDesc s = test::small_box(16, 4, 4000, 3);
    s.time = {0, 60, 6, 24};
    test::Rendered r = test::render_all(s);
    ASSERT_EQ(r.frames.size(), 6u);
    for (size_t i = 0; i < r.steady.size(); ++i) EXPECT_NEAR(r.frames.back()[i], r.steady[i], 1e-5 * (1 + r.steady[i]));
    EXPECT_GT(test::mean(r.steady), 0.0);
    // Constant frames never lose light: each pixel is non-decreasing frame by frame.
    for (size_t k = 1; k < r.frames.size(); ++k)
        for (size_t i = 0; i < r.steady.size(); ++i) ASSERT_GE(r.frames[k][i], r.frames[k - 1][i]);
}

TEST(EmissionModes, WiderPulseIsTheSumOfNarrowOnes) {
    SceneDesc s = test::small_box(12, 3, 3000, 4);
    s.time = {0, 24, 12, 24};
    RenderContext narrow_ctx(s);
    s.emission.mode = EmissionMode::Pulse;
    s.emission.width_ns = 3 * 2.0;  // three frames wide
    s.emission.width_frames = 3;
    RenderContext wide_ctx(s);
    ASSERT_EQ(wide_ctx.timeline.pulse_buckets, 3);
    std::vector<std::vector<float>> n(12), wide(12);
    FramesInMemory sink;
    sink.on_section_rendered = [&](int, const SectionBuffer& buffer) {  // assembled 1 and 3 frames wide
        FrameAssembler w(buffer, EmissionMode::Pulse, 3), narrow(buffer, EmissionMode::Pulse, 1);
        for (int k = 0; k < 12; ++k) narrow.frame(k, n[k]);
        for (int k = 2; k < 12; ++k) w.frame(k, wide[k]);
    };
    render_frames(wide_ctx, {Strategy::Single, 1, 3, 3000}, sink);
    for (int k = 2; k < 12; ++k) {
        const std::vector<float>& w = wide[k];
        ASSERT_FALSE(w.empty());
        for (size_t i = 0; i < w.size(); ++i) ASSERT_NEAR(w[i], n[k][i] + n[k - 1][i] + n[k - 2][i], 1e-4 * (1 + w[i]));
    }
}

}  // namespace
}  // namespace sl
