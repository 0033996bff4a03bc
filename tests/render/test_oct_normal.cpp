// Packed normals (core/oct_normal.h): photon records and visible points keep their normals in
// 4 bytes. The gather compares them against a 45-degree threshold, so what matters is that the
// round trip keeps the direction to well under a degree everywhere on the sphere, including
// the axes, the folded lower half and the seams between octants.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/oct_normal.h"
#include "core/rng.h"
#include "core/sampling.h"

namespace sl {
namespace {

// atan2(|a x b|, a.b): exact for small angles, where acos of a float dot product is not.
double angle_between(Vec3 a, Vec3 b) { return std::atan2(length(cross(a, b)), dot(a, b)); }

TEST(OctNormal, RoundTripKeepsDirectionWithinATenthOfAMilliradian) {
    std::vector<Vec3> dirs = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1},
                              normalize(Vec3{1, 1, 1}), normalize(Vec3{-1, -1, -1}), normalize(Vec3{1, -1e-7f, -1}),
                              normalize(Vec3{1e-8f, 1e-8f, -1})};
    Rng rng(11, 0, 0);
    for (int i = 0; i < 200000; ++i) dirs.push_back(sample_uniform_sphere(rng.uniform(), rng.uniform()));
    double worst = 0;
    for (Vec3 n : dirs) {
        Vec3 back = decode_normal(encode_normal(n));
        ASSERT_TRUE(is_finite(back));
        EXPECT_NEAR(length(back), 1.0, 1e-6);
        worst = std::max(worst, angle_between(n, back));
    }
    // 16-bit coordinates over [-1, 1]: a step of 3e-5, about 1e-4 rad at worst near the folds.
    EXPECT_LT(worst, 1e-4);
}

TEST(OctNormal, UnnormalizedDecodeKeepsTheSignOfEveryDotProduct) {
    // The gather tests cos(angle) >= 0.7 without normalising: the decoded vector must point the
    // same way and have a length the test can divide out (between 1/sqrt(3) and 1).
    Rng rng(12, 0, 0);
    for (int i = 0; i < 100000; ++i) {
        Vec3 n = sample_uniform_sphere(rng.uniform(), rng.uniform());
        Vec3 raw = decode_normal_unnormalized(encode_normal(n));
        float len = length(raw);
        EXPECT_GE(len, 1 / std::sqrt(3.0f) - 1e-4f);
        EXPECT_LE(len, 1 + 1e-4f);
        EXPECT_GT(dot(raw, n), 0.99f * len);
    }
}

}  // namespace
}  // namespace sl
