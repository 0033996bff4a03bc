// A medium at its extremes: sigma_t = 0 renders exactly as vacuum; an optical depth of 50 on
// every camera ray leaves (almost) nothing, and nothing non-finite, whether the medium
// absorbs or scatters.
#include <cmath>

#include "hard_helpers.h"

namespace sl::hard {
namespace {

SceneDesc box_with_medium(Vec3 sigma_a, Vec3 sigma_s) {
    SceneDesc s = closed_box(12, 3, 2000);
    s.medium.present = true;
    s.medium.sigma_a = sigma_a;
    s.medium.sigma_s = sigma_s;
    s.medium.g = 0.3f;
    return s;
}

double max_value(const Rendered& r) {
    double m = 0;
    for (float v : r.steady) m = std::max(m, double(v));
    for (const Image& f : r.frames)
        for (float v : f) m = std::max(m, double(v));
    return m;
}

TEST(MediumExtremes, ZeroExtinctionRendersExactlyAsVacuum) {
    Rendered vacuum = render(closed_box(12, 3, 2000));
    Rendered none = render(box_with_medium(Vec3(0), Vec3(0)));
    ASSERT_EQ(none.buffer_non_finite + none.image_non_finite(), 0u);
    EXPECT_EQ(none.steady, vacuum.steady);
    ASSERT_EQ(none.frames.size(), vacuum.frames.size());
    for (size_t k = 0; k < none.frames.size(); ++k) EXPECT_EQ(none.frames[k], vacuum.frames[k]) << "frame " << k;
}

TEST(MediumExtremes, OpticalDepthFiftyAbsorbingOrScattering) {
    // Every surface the camera sees is at least ~1 m away: sigma_t = 50 /m gives an optical
    // depth of 50 or more on every camera ray (transmittance < 2e-22).
    const double vacuum_max = max_value(render(closed_box(12, 3, 2000)));
    ASSERT_GT(vacuum_max, 0);
    {
        Rendered r = render(box_with_medium(Vec3(50), Vec3(0)));
        EXPECT_EQ(r.buffer_non_finite, 0u);
        EXPECT_EQ(r.image_non_finite(), 0u);
        EXPECT_LE(max_value(r), 1e-15 * vacuum_max);  // absorbed: surfaces and emitter fade out
    }
    {
        // Scattering only (albedo 1): light random-walks in 2 cm steps; what reaches the camera
        // is in-scattered light near it: finite, and not above the light's radiance (17) by much.
        Rendered r = render(box_with_medium(Vec3(0), Vec3(50)));
        EXPECT_EQ(r.buffer_non_finite, 0u);
        EXPECT_EQ(r.image_non_finite(), 0u);
        EXPECT_LE(max_value(r), 100.0);
        EXPECT_GE(mean(r.steady), 0.0);
    }
}

}  // namespace
}  // namespace sl::hard
