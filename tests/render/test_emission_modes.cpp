// One convergence gives both videos: pulse frames (w = delta) sum to the last constant frame
// minus what arrived before start, and the last constant frame equals steady.exr once end_ns
// is past every path's length.
#include <gtest/gtest.h>

#include "render_helpers.h"
#include "scenes_for_tests.h"

namespace sl {
namespace {

TEST(EmissionModes, PulseFramesSumToLastConstantFrameMinusBeforeStart) {
    SceneDesc s = test::small_box(16, 4, 4000, 4);
    s.time = {5, 17, 12, 24};  // starts after light has already reached the walls
    RenderContext ctx(s);
    SectionCounters counters;
    SectionLayout layout = make_section(ctx.timeline, ctx.scene.emission.mode, 1, 1, 0);
    SectionRun run = render_section(ctx, layout, s.render.passes, s.render.photons_per_pass, counters);
    FrameAssembler constant(*run.buffer, EmissionMode::Constant, 1), pulse(*run.buffer, EmissionMode::Pulse, 1);
    std::vector<float> last, frame, sum(ctx.pixels() * 3, 0.0f);
    for (int k = 0; k < s.time.frames; ++k) {
        constant.frame(k, last);
        pulse.frame(k, frame);
        for (size_t i = 0; i < sum.size(); ++i) sum[i] += frame[i];
    }
    double before = 0, total_sum = 0, total_last = 0;
    for (size_t p = 0; p < ctx.pixels(); ++p)
        for (int c = 0; c < 3; ++c) before += run.buffer->slot(p, 0)[c] / float(run.buffer->passes_done);
    for (size_t i = 0; i < sum.size(); ++i) {
        EXPECT_NEAR(sum[i], last[i] - run.buffer->slot(i / 3, 0)[i % 3] / float(run.buffer->passes_done),
                    1e-4 * (1 + last[i]));
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
    ASSERT_EQ(wide_ctx.pulse_buckets, 3);
    SectionCounters counters;
    SectionRun run = render_section(wide_ctx, make_section(wide_ctx.timeline, wide_ctx.scene.emission.mode, 3, 1, 0), 3, 3000, counters);
    FrameAssembler wide(*run.buffer, EmissionMode::Pulse, 3), narrow(*run.buffer, EmissionMode::Pulse, 1);
    std::vector<std::vector<float>> n(12);
    std::vector<float> w;
    for (int k = 0; k < 12; ++k) narrow.frame(k, n[k]);
    for (int k = 2; k < 12; ++k) {
        wide.frame(k, w);
        for (size_t i = 0; i < w.size(); ++i) ASSERT_NEAR(w[i], n[k][i] + n[k - 1][i] + n[k - 2][i], 1e-4 * (1 + w[i]));
    }
}

}  // namespace
}  // namespace sl
