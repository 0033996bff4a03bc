// The beam estimate's automatic radius (render_context.h): the footprint rule, widened where the
// volume photons of a pass are too sparse for a beam query across the medium to meet about
// forty of them. A hazy box: a million photon paths a pass fill it densely, ten thousand do not.
#include <gtest/gtest.h>

#include <cmath>

#include "scenes_for_tests.h"
#include "stages/render/render_context.h"

namespace sl {
namespace {

SceneDesc hazy_box(int64_t photons) {
    SceneDesc s = test::small_box(256, 1, photons, 8);  // the footprint rule well under its cap
    s.medium.present = true;
    s.medium.sigma_a = Vec3(0.05f);
    s.medium.sigma_s = Vec3(0.5f);
    return s;
}

TEST(BeamRadius, SparseVolumePhotonsWidenTheAutomaticRadiusAndDenseOnesKeepIt) {
    const RenderContext dense(hazy_box(1000000));
    ASSERT_TRUE(dense.medium.has_value());
    const float rule = choose_volume_radius(hazy_box(1000000), *dense.medium, dense.camera);
    EXPECT_FLOAT_EQ(dense.volume_radius, rule);
    // Few paths a pass: wider, at most 4x.
    const float r10k = RenderContext(hazy_box(10000)).volume_radius;
    const float r20k = RenderContext(hazy_box(20000)).volume_radius;
    const float r100 = RenderContext(hazy_box(100)).volume_radius;
    std::printf("footprint rule %.4f m; widened: 20000 paths %.4f, 10000 paths %.4f, 100 paths %.4f\n", rule, r20k,
                r10k, r100);
    EXPECT_GT(r20k, 1.2f * rule);
    EXPECT_LT(r10k, 3.9f * rule);
    EXPECT_FLOAT_EQ(r100, 4 * rule);
    // Between the bounds the radius holds the count a query meets: twice the photons, 1/sqrt(2)
    // the radius (the pilot is the same for both).
    EXPECT_NEAR(r20k / r10k, 1 / std::sqrt(2.0f), 1e-4f);
    // Every seed of a scene gets the same radius (the pilot has a seed of its own).
    SceneDesc s = hazy_box(10000);
    s.render.seed = 7;
    EXPECT_EQ(RenderContext(s).volume_radius, r10k);
    // The scene's own radius is kept as it is.
    s.render.radius = 0.01f;
    EXPECT_FLOAT_EQ(RenderContext(s).volume_radius, 0.01f);
}

}  // namespace
}  // namespace sl
