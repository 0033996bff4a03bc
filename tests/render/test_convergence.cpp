// Progressive photon mapping converges: the steady image's error against a long run falls as
// passes grow; the same seed gives the same image, whatever the thread count.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "render_helpers.h"
#include "scenes_for_tests.h"

namespace sl {
namespace {

TEST(Convergence, SteadyErrorFallsWithPasses) {
    SceneDesc ref_scene = test::small_box(16, 192, 20000);
    ref_scene.time.frames = 1;
    ref_scene.render.seed = 99;
    test::Rendered ref = test::render_all(ref_scene);
    double err[2];
    int passes[2] = {3, 24};
    for (int i = 0; i < 2; ++i) {
        SceneDesc s = ref_scene;
        s.render.seed = 7;
        s.render.passes = passes[i];
        err[i] = test::rmse(test::render_all(s).steady, ref.steady);
    }
    // 8x the passes: PPM's error falls roughly as passes^(-1/3) or faster; ask for a clear drop.
    EXPECT_LT(err[1], 0.75 * err[0]) << err[0] << " -> " << err[1];
    EXPECT_GT(test::mean(ref.steady), 0.0);
}

TEST(Determinism, SameSeedSameImageAnyThreadCount) {
    SceneDesc s = test::small_box(16, 3, 5000);
    test::Rendered a, b, c;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        a = test::render_all(s);
    }
    {
        tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
        b = test::render_all(s);
        c = test::render_all(s);
    }
    EXPECT_EQ(b.steady, c.steady);  // bit for bit
    EXPECT_EQ(a.steady, b.steady);  // photons are batched and summed per pixel in a fixed order
    for (size_t k = 0; k < a.frames.size(); ++k) EXPECT_EQ(a.frames[k], b.frames[k]);
    s.render.seed = 2;
    EXPECT_NE(test::render_all(s).steady, a.steady);
}

TEST(Sections, SplitRenderMatchesSingleWithinNoise) {
    SceneDesc s = test::small_box(16, 6, 8000);
    test::Rendered one = test::render_all(s, 1);
    test::Rendered four = test::render_all(s, 4);
    ASSERT_EQ(one.frames.size(), four.frames.size());
    // Same seeds: the sections trace the same photon paths (cut early where they cannot
    // reach the section; earlier light carried over from the section before), so only the
    // radius schedules differ: each section's radii shrink on the photons it keeps.
    for (size_t k = 0; k < one.frames.size(); ++k) {
        double m = test::mean(one.frames[k]);
        EXPECT_NEAR(test::mean(four.frames[k]), m, 0.03 * m + 1e-6) << "frame " << k;
    }
    const double m = test::mean(one.steady);
    EXPECT_NEAR(test::mean(four.steady), m, 0.03 * m);
    // Constant light only ever adds: every pixel of every frame is at least its value in the
    // frame before, across section boundaries too (a section starts from the last frame of the
    // one before, then adds its own buckets; independently gathered sections would not keep this).
    // At a boundary, to float rounding: the carried frame re-enters a sum over the passes.
    auto at_least = [](float later, float earlier) { return later >= earlier - 4e-7f * earlier; };
    for (size_t k = 1; k < four.frames.size(); ++k)
        for (size_t i = 0; i < four.frames[k].size(); ++i)
            ASSERT_TRUE(at_least(four.frames[k][i], four.frames[k - 1][i]))
                << "frame " << k << ", value " << i << ": " << four.frames[k][i] << " after " << four.frames[k - 1][i];
    for (size_t i = 0; i < four.steady.size(); ++i)
        ASSERT_TRUE(at_least(four.steady[i], four.frames.back()[i])) << "value " << i;
}

}  // namespace
}  // namespace sl
