// The direction samplers of the photon paths against independent numbers: turn_sincos against
// the C library over every 24-bit uniform, and cosine-weighted directions against the analytic
// law of their angle to the normal (P(cos theta <= x) = x^2) and a uniform azimuth.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/rng.h"
#include "core/sampling.h"
#include "foundation/turn_sincos.h"

namespace sl {
namespace {

TEST(SamplingWarps, TurnSincosMatchesTheLibraryOnEveryUniform) {
    double worst = 0;
    for (uint32_t k = 0; k < (1u << 24); ++k) {
        const float u = static_cast<float>(k) * 0x1p-24f;
        float c, s;
        turn_sincos(u, c, s);
        const double phi = 2 * 3.14159265358979323846 * static_cast<double>(u);
        worst = std::max({worst, std::abs(c - std::cos(phi)), std::abs(s - std::sin(phi))});
    }
    // A float's spacing just below 1 is 6e-8: a few of them, no more.
    EXPECT_LT(worst, 3e-7) << "largest error against the library";
}

TEST(SamplingWarps, CosineHemisphereFollowsTheCosineLaw) {
    Rng rng(5, 1);
    const int n = 400000, bins = 10;
    // Normals of every kind, the poles of the basis included.
    const std::vector<Vec3> normals = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, normalize(Vec3{0.3f, -0.8f, 0.52f}),
                                       normalize(Vec3{-1e-4f, 2e-4f, -1})};
    for (const Vec3& nrm : normals) {
        std::vector<int> hist(bins, 0);
        int quadrant[4] = {0, 0, 0, 0};
        Vec3 t, b;
        make_basis(nrm, t, b);
        double worst_length = 0;
        for (int i = 0; i < n; ++i) {
            const Vec3 d = sample_cosine_hemisphere(nrm, rng.uniform(), rng.uniform());
            worst_length = std::max(worst_length, std::abs(static_cast<double>(length(d)) - 1));
            const float c = dot(d, nrm);
            ASSERT_GE(c, -1e-6f);
            // cos^2 is uniform under the cosine law: equal counts in equal bins of cos^2.
            ++hist[std::min(bins - 1, static_cast<int>(c * c * bins))];
            ++quadrant[(dot(d, t) < 0 ? 1 : 0) + (dot(d, b) < 0 ? 2 : 0)];
        }
        EXPECT_LT(worst_length, 1e-6);
        const double expect = static_cast<double>(n) / bins, sigma = std::sqrt(expect);
        for (int k = 0; k < bins; ++k) EXPECT_NEAR(hist[k], expect, 5 * sigma) << "cos^2 bin " << k;
        for (int q = 0; q < 4; ++q) EXPECT_NEAR(quadrant[q], n / 4.0, 5 * std::sqrt(n / 4.0)) << "azimuth quadrant " << q;
    }
}

}  // namespace
}  // namespace sl
