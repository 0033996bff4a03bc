// The draws of a split camera path (stratified_draw, core/glossy_path.h): n draws that cover the
// BSDF's three numbers evenly, shifted by one random offset. Checked on Blender 3.x's rough glass
// seen 72 degrees from its normal (the glass cube's top in bench/blender): each draw is uniform
// on its own, so the n draws' mean weight keeps the albedo's mean; the lobe choice is stratified
// (of 32 branches, reflection takes 32 P give or take one, every time), and the spread of the
// n draws' mean over offsets is several times smaller than with independent draws.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "core/bsdf/bsdf.h"
#include "core/glossy_path.h"

namespace sl::test {
namespace {

bsdf::Bsdf rough_glass() {
    bsdf::Bsdf b;
    b.kind = bsdf::Kind::MetallicRoughness;
    b.blender3_base = true;
    b.alpha = bsdf::alpha_of_roughness(0.2f);
    b.base = Vec3(1);
    b.ior = 1.45f;
    b.transmission = 1;
    return bsdf::cache_layer_averages(b);
}

const float kTheta = 72 * 3.14159265f / 180;
const Vec3 kWo{std::sin(kTheta), 0, std::cos(kTheta)};

struct SplitMean {
    double weight = 0;  // the n draws' mean weight (grey)
    int reflected = 0;  // of the n draws, those that stayed above the surface
};

SplitMean split_mean(const bsdf::Bsdf& b, int n, bool stratified, std::mt19937& gen) {
    std::uniform_real_distribution<float> u01(0, 1);
    const BsdfDraw offset{u01(gen), u01(gen), u01(gen)};
    SplitMean r;
    for (int k = 0; k < n; ++k) {
        const BsdfDraw u = stratified ? stratified_draw(k, n, offset) : BsdfDraw{u01(gen), u01(gen), u01(gen)};
        const bsdf::Sample s = bsdf::sample(b, kWo, u.uc, u.u1, u.u2);
        if (!s.valid) continue;
        r.weight += (s.weight.x + s.weight.y + s.weight.z) / 3 / n;
        r.reflected += s.wi.z > 0;
    }
    return r;
}

TEST(StratifiedDraw, EachDrawIsUniformAndStaysBelowOne) {
    // Over random offsets, the k-th draw of n falls in each of 8 bins of every coordinate equally.
    std::mt19937 gen(7);
    std::uniform_real_distribution<float> u01(0, 1);
    const int n = 32, trials = 16000;
    for (int k : {0, 5, 31}) {
        std::vector<int> bins(24, 0);
        for (int t = 0; t < trials; ++t) {
            const BsdfDraw u = stratified_draw(k, n, {u01(gen), u01(gen), u01(gen)});
            ASSERT_TRUE(u.uc >= 0 && u.uc < 1 && u.u1 >= 0 && u.u1 < 1 && u.u2 >= 0 && u.u2 < 1);
            ++bins[static_cast<int>(u.uc * 8)];
            ++bins[8 + static_cast<int>(u.u1 * 8)];
            ++bins[16 + static_cast<int>(u.u2 * 8)];
        }
        for (int c : bins) EXPECT_NEAR(c, trials / 8.0, 5 * std::sqrt(trials / 8.0)) << "draw " << k;
    }
    // An offset just below 1 still gives numbers below 1.
    const BsdfDraw u = stratified_draw(31, 32, {0x1.fffffep-1f, 0x1.fffffep-1f, 0x1.fffffep-1f});
    EXPECT_LT(std::max({u.uc, u.u1, u.u2}), 1.0f);
}

TEST(StratifiedDraw, TheSplitsLobeChoiceIsStratifiedAndItsMeanKeptWithASmallerSpread) {
    const bsdf::Bsdf b = rough_glass();
    const int n = 32, trials = 4000;
    // The share of the independent draws that reflect is the sampler's own probability P.
    std::mt19937 gen(11);
    double independent_reflected = 0;
    double sum[2] = {0, 0}, sq[2] = {0, 0};
    int reflected_min = n, reflected_max = 0, independent_min = n, independent_max = 0;
    for (int t = 0; t < trials; ++t) {
        const SplitMean s = split_mean(b, n, true, gen), i = split_mean(b, n, false, gen);
        sum[0] += s.weight;
        sq[0] += s.weight * s.weight;
        sum[1] += i.weight;
        sq[1] += i.weight * i.weight;
        reflected_min = std::min(reflected_min, s.reflected);
        reflected_max = std::max(reflected_max, s.reflected);
        independent_min = std::min(independent_min, i.reflected);
        independent_max = std::max(independent_max, i.reflected);
        independent_reflected += static_cast<double>(i.reflected) / trials;
    }
    // n P, give or take one (a reflection lost below the macro-surface, at this angle rare).
    EXPECT_GE(reflected_min, static_cast<int>(std::floor(independent_reflected)) - 1);
    EXPECT_LE(reflected_max, static_cast<int>(std::ceil(independent_reflected)) + 1);
    EXPECT_GT(independent_max - independent_min, 3);  // what the stratification takes away
    const double mean_s = sum[0] / trials, mean_i = sum[1] / trials;
    const double var_s = sq[0] / trials - mean_s * mean_s, var_i = sq[1] / trials - mean_i * mean_i;
    // The same mean (the independent draws' standard error sets the tolerance).
    EXPECT_NEAR(mean_s, mean_i, 4 * std::sqrt(var_i / trials));
    EXPECT_LT(var_s * 4, var_i);
    std::printf("[stratified split, rough glass at 72 deg, n = %d] n P %.2f: reflected %d-%d (independent "
                "%d-%d); mean weight %.4f vs %.4f, spread %.4f vs %.4f\n",
                n, independent_reflected, reflected_min, reflected_max, independent_min, independent_max, mean_s, mean_i,
                std::sqrt(var_s), std::sqrt(var_i));
}

// A branch's draw at its next glossy vertex (shuffled_draw): uniform on its own and unrelated
// to the branch's first draw, while over the n branches each coordinate is stratified.
TEST(StratifiedDraw, ABranchsSecondDrawIsUniformIndependentOfItsFirstAndStratifiedOverTheBranches) {
    std::mt19937 gen(5);
    std::uniform_real_distribution<float> u01(0, 1);
    const int n = 32, trials = 20000;
    std::vector<int> bins(24, 0);
    double s1 = 0, s2 = 0, s12 = 0, q1 = 0, q2 = 0;  // the first and second uc of branch 7
    for (int t = 0; t < trials; ++t) {
        const BsdfDraw first{u01(gen), u01(gen), u01(gen)}, second{u01(gen), u01(gen), u01(gen)};
        const BranchShuffle shuffle{static_cast<uint32_t>(gen()) | 1u, static_cast<uint32_t>(gen())};
        const BsdfDraw a = stratified_draw(7, n, first), b = shuffled_draw(7, n, shuffle, second);
        ASSERT_TRUE(b.uc >= 0 && b.uc < 1 && b.u1 >= 0 && b.u1 < 1 && b.u2 >= 0 && b.u2 < 1);
        ++bins[static_cast<int>(b.uc * 8)];
        ++bins[8 + static_cast<int>(b.u1 * 8)];
        ++bins[16 + static_cast<int>(b.u2 * 8)];
        s1 += a.uc, s2 += b.uc, s12 += a.uc * b.uc, q1 += a.uc * a.uc, q2 += b.uc * b.uc;
        if (t < 200) {  // over the branches: one second draw in each n-th of [0, 1) in uc
            std::vector<int> strata(n, 0);
            for (int k = 0; k < n; ++k) {
                const float uc = shuffled_draw(k, n, shuffle, {0, second.u1, second.u2}).uc;
                ++strata[std::min(n - 1, static_cast<int>(uc * n + 1e-4f))];
            }
            for (int c : strata) ASSERT_EQ(c, 1);
        }
    }
    for (int c : bins) EXPECT_NEAR(c, trials / 8.0, 5 * std::sqrt(trials / 8.0));
    const double m1 = s1 / trials, m2 = s2 / trials;
    const double corr = (s12 / trials - m1 * m2) / std::sqrt((q1 / trials - m1 * m1) * (q2 / trials - m2 * m2));
    EXPECT_LT(std::abs(corr), 4 / std::sqrt(static_cast<double>(trials)));
}

// Through a slab of the rough glass (top face, then bottom face from inside, the cube's path
// from the camera to the floor beneath): the n branches' mean throughput out of the bottom with
// second draws from shuffled_draw against independent ones. The same mean, a smaller spread:
// the branches that reflect at the bottom are stratified too.
TEST(StratifiedDraw, SecondDrawsThroughASlabKeepTheMeanWithASmallerSpread) {
    const bsdf::Bsdf b = rough_glass();
    const int n = 32, trials = 4000;
    std::mt19937 gen(17);
    std::uniform_real_distribution<float> u01(0, 1);
    double sum[2] = {0, 0}, sq[2] = {0, 0};
    for (int t = 0; t < trials; ++t) {
        const BsdfDraw first{u01(gen), u01(gen), u01(gen)}, second{u01(gen), u01(gen), u01(gen)};
        const BranchShuffle shuffle{static_cast<uint32_t>(gen()) | 1u, static_cast<uint32_t>(gen())};
        double mean[2] = {0, 0};
        for (int k = 0; k < n; ++k) {
            const BsdfDraw u = stratified_draw(k, n, first);
            const bsdf::Sample top = bsdf::sample(b, kWo, u.uc, u.u1, u.u2);
            const BsdfDraw independent{u01(gen), u01(gen), u01(gen)};
            if (!top.valid || top.wi.z >= 0) continue;  // reflected at the top: not through
            // The bottom face's frame (normal -z, tangents x and -y): the path arrives from inside.
            const Vec3 wo2{-top.wi.x, top.wi.y, top.wi.z};
            for (int m = 0; m < 2; ++m) {
                const BsdfDraw v = m == 0 ? shuffled_draw(k, n, shuffle, second) : independent;
                const bsdf::Sample bottom = bsdf::sample(b, wo2, v.uc, v.u1, v.u2);
                if (!bottom.valid || bottom.wi.z <= 0) continue;  // back inside: not out of the bottom
                mean[m] += (top.weight.x * bottom.weight.x) / n;
            }
        }
        for (int m = 0; m < 2; ++m) sum[m] += mean[m], sq[m] += mean[m] * mean[m];
    }
    const double mean_s = sum[0] / trials, mean_i = sum[1] / trials;
    const double var_s = sq[0] / trials - mean_s * mean_s, var_i = sq[1] / trials - mean_i * mean_i;
    EXPECT_NEAR(mean_s, mean_i, 4 * std::sqrt(var_i / trials));
    EXPECT_LT(var_s * 1.5, var_i);  // measured: 1.64x less variance (spread 0.053 against 0.068)
    std::printf("[through a rough glass slab, n = %d] mean %.4f vs %.4f (independent second draws), "
                "spread %.4f vs %.4f\n",
                n, mean_s, mean_i, std::sqrt(var_s), std::sqrt(var_i));
}

}  // namespace
}  // namespace sl::test
