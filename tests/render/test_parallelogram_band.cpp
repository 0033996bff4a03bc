// The draw of a parallelogram's points by their distance to a point (core/parallelogram_band.h),
// checked against a fine grid over the parallelogram: each band's area and the integral of
// cos / d^2 over it, the draws inside the band and the parallelogram, and the distances spanned.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/parallelogram_band.h"
#include "core/rng.h"

namespace sl {
namespace {

struct Case {
    Vec3 x, corner, e1, e2;
};

// A skewed parallelogram seen from above its inside, from beside it, from almost in its plane,
// from far away, and a rectangle seen from above a corner.
std::vector<Case> cases() {
    const Vec3 c(-0.3f, 2.0f, -0.2f), e1(0.6f, 0.0f, 0.1f), e2(0.15f, 0.0f, 0.45f);
    return {
        {Vec3(0.0f, 1.2f, 0.05f), c, e1, e2},
        {Vec3(0.9f, 1.5f, 0.8f), c, e1, e2},
        {Vec3(1.0f, 1.999f, 0.1f), c, e1, e2},
        {Vec3(3.0f, -4.0f, 2.0f), c, e1, e2},
        {Vec3(-0.3f, 1.9f, -0.2f), c, Vec3(0.5f, 0, 0), Vec3(0, 0, 0.4f)},
    };
}

// The integrals over the band [d0, d1) by a midpoint rule on an n x n grid of the parameters.
struct GridIntegrals {
    double area = 0, cos_over_d2 = 0;
};
GridIntegrals grid(const Case& k, double d0, double d1, int n = 1500) {
    const Vec3 nrm = normalize(cross(k.e1, k.e2));
    const double cell = length(cross(k.e1, k.e2)) / (double(n) * n);
    GridIntegrals g;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const Vec3 y = k.corner + k.e1 * ((i + 0.5f) / n) + k.e2 * ((j + 0.5f) / n);
            const Vec3 v = y - k.x;
            const double d = length(v);
            if (d < d0 || d >= d1) continue;
            g.area += cell;
            g.cos_over_d2 += cell * std::abs(dot(v, nrm)) / (d * d * d);
        }
    return g;
}

TEST(ParallelogramBand, BandsHoldTheGridsAreaAndIntegral) {
    for (const Case& k : cases()) {
        const ParallelogramFromPoint q(k.x, k.corner, k.e1, k.e2);
        ASSERT_TRUE(q.valid());
        const Vec3 nrm = normalize(cross(k.e1, k.e2));
        const double total_area = length(cross(k.e1, k.e2));
        const int bands = 6;
        const double span = q.max_distance() - q.min_distance();
        double area_sum = 0;
        for (int b = 0; b < bands; ++b) {
            const double d0 = q.min_distance() + span * b / bands, d1 = q.min_distance() + span * (b + 1) / bands;
            const GridIntegrals want = grid(k, d0, d1);
            // Stratified draws (a 400 x 400 lattice, each shifted at random): the estimates' own
            // error is far below the tolerance.
            Rng rng(7, 3, b, 0);
            const int m = 400;
            double area = 0, integral = 0;
            for (int i = 0; i < m; ++i)
                for (int j = 0; j < m; ++j) {
                    Vec3 y;
                    double w;
                    const float u1 = (i + rng.uniform()) / m, u2 = (j + rng.uniform()) / m;
                    if (!q.sample_band(d0, d1, u1, u2, y, w)) continue;
                    const Vec3 v = y - k.x;
                    const double d = length(v);
                    ASSERT_GE(d, d0 - 1e-4);
                    ASSERT_LT(d, d1 + 1e-4);
                    // Inside the parallelogram: its parameters within [0, 1].
                    const Vec3 r = y - k.corner;
                    const Vec3 a = cross(r, k.e2), c = cross(k.e1, r), n = cross(k.e1, k.e2);
                    const double s = dot(a, n) / dot(n, n), t = dot(c, n) / dot(n, n);
                    ASSERT_GT(s, -1e-4);
                    ASSERT_LT(s, 1 + 1e-4);
                    ASSERT_GT(t, -1e-4);
                    ASSERT_LT(t, 1 + 1e-4);
                    area += w;
                    integral += w * std::abs(dot(v, nrm)) / (d * d * d);
                }
            area /= double(m) * m;
            integral /= double(m) * m;
            area_sum += area;
            EXPECT_NEAR(area, want.area, 2e-3 * total_area) << "band " << b;
            EXPECT_NEAR(integral, want.cos_over_d2, 3e-3 * want.cos_over_d2 + 1e-6) << "band " << b;
        }
        EXPECT_NEAR(area_sum, total_area, 2e-3 * total_area);
    }
}

TEST(ParallelogramBand, DistancesSpannedAreTheNearestAndFarthestPoints) {
    for (const Case& k : cases()) {
        const ParallelogramFromPoint q(k.x, k.corner, k.e1, k.e2);
        double lo = INFINITY, hi = 0;
        const int n = 600;
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j) {
                const double d = length(k.corner + k.e1 * (float(i) / n) + k.e2 * (float(j) / n) - k.x);
                lo = std::min(lo, d);
                hi = std::max(hi, d);
            }
        EXPECT_NEAR(q.min_distance(), lo, 1e-3 * hi);
        EXPECT_NEAR(q.max_distance(), hi, 1e-5 * hi);
        EXPECT_LE(q.min_distance(), lo + 1e-6);
    }
}

TEST(ParallelogramBand, EmptyBandsAndDegenerateQuadsDrawNothing) {
    const Case k = cases()[0];
    const ParallelogramFromPoint q(k.x, k.corner, k.e1, k.e2);
    Vec3 y;
    double w = 1;
    EXPECT_FALSE(q.sample_band(0, q.min_distance() * 0.99, 0.5f, 0.5f, y, w));
    EXPECT_EQ(w, 0);
    EXPECT_FALSE(q.sample_band(q.max_distance() * 1.01, 1e9, 0.5f, 0.5f, y, w));
    const ParallelogramFromPoint flat(k.x, k.corner, k.e1, k.e1 * 2.0f);
    EXPECT_FALSE(flat.valid());
    EXPECT_FALSE(flat.sample_band(0, 1e9, 0.5f, 0.5f, y, w));
}

}  // namespace
}  // namespace sl
