// Photon paths' first numbers from a randomised Halton sequence (core/photon_qmc.h). Checked
// as numbers (each point uniform, each dimension stratified over a pass), and by what they
// are for: the light a wall gathers from a floor one bounce away varies far less from seed to
// seed, with the same mean as independent numbers (the other way through the code).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/photon_qmc.h"
#include "light_paths_helpers.h"

namespace sl {
namespace {

TEST(PhotonQmc, EachDimensionIsStratifiedOverAPassAndEveryPointIsInTheUnitCube) {
    // The first b^k indices put exactly one point in each interval of width b^-k (unshifted),
    // and the shift moves them all together (mod 1): counted with the shift undone.
    const PhotonQmc qmc(7, 3);
    float origin[PhotonQmc::kDims];
    qmc.point(0, origin);  // radical inverse of 0 is 0: the point is the shift itself
    const int bases[PhotonQmc::kDims] = {2, 3, 5, 7, 11, 13, 17, 19};
    for (int j = 0; j < PhotonQmc::kDims; ++j) {
        const int b = bases[j], n = b * b;
        std::vector<int> count(static_cast<size_t>(n), 0);
        float u[PhotonQmc::kDims];
        for (int i = 0; i < n; ++i) {
            qmc.point(static_cast<uint64_t>(i), u);
            ASSERT_GE(u[j], 0.0f);
            ASSERT_LT(u[j], 1.0f);
            float v = u[j] - origin[j];
            if (v < 0) v += 1;
            const int cell = std::min(n - 1, static_cast<int>(v * n + 1e-4f));
            ++count[static_cast<size_t>(cell)];
        }
        for (int c = 0; c < n; ++c) EXPECT_EQ(count[static_cast<size_t>(c)], 1) << "dimension " << j << " cell " << c;
    }
    EXPECT_FLOAT_EQ(PhotonQmc::radical_inverse(6, 2), 0.375f);   // 110 -> 0.011
    EXPECT_FLOAT_EQ(PhotonQmc::radical_inverse(5, 3), 7.0f / 9);  // 12 -> 0.21
}

TEST(PhotonQmc, AWalkGivesEachIndexsPoint) {
    // The batches' incremental digits against the direct radical inverse, across carries in
    // every base (from an index whose low digits are all at their largest in base 2 and 3).
    const PhotonQmc qmc(3, 9);
    const uint64_t first = (uint64_t(1) << 20) - 5;
    PhotonQmc::Walk walk(qmc, first);
    for (uint64_t i = first; i < first + 5000; ++i) {
        float a[PhotonQmc::kDims], b[PhotonQmc::kDims];
        walk.next(a);
        qmc.point(i, b);
        for (int j = 0; j < PhotonQmc::kDims; ++j) ASSERT_NEAR(a[j], b[j], 1e-6f) << "index " << i << " dimension " << j;
    }
    // The photon pass's chunks (fill: dimension by dimension), the same points exactly, chunk
    // after chunk across the same carries.
    PhotonQmc::Walk chunks(qmc, first);
    std::vector<float> u(300 * PhotonQmc::kDims);
    for (uint64_t start = first; start < first + 3000; start += 300) {
        chunks.fill(u.data(), 300);
        for (uint64_t i = start; i < start + 300; ++i) {
            float b[PhotonQmc::kDims];
            qmc.point(i, b);
            for (int j = 0; j < PhotonQmc::kDims; ++j)
                ASSERT_EQ(u[(i - start) * PhotonQmc::kDims + j], b[j]) << "index " << i << " dimension " << j;
        }
    }
}

TEST(PhotonQmc, ShiftsAreUniformOverPasses) {
    // Every photon's point is uniform because the pass's shift is: the mean of point 5's first
    // dimension over 4000 passes is 1/2 within 4 standard errors.
    double sum = 0;
    const int passes = 4000;
    for (int p = 0; p < passes; ++p) {
        float u[PhotonQmc::kDims];
        PhotonQmc(1, static_cast<uint64_t>(p)).point(5, u);
        sum += u[0];
    }
    EXPECT_NEAR(sum / passes, 0.5, 4 * std::sqrt(1.0 / 12 / passes));
}

// A white floor z = 0 and a wall x = 1 facing it, a spot 1.5 m over the floor aimed down (its
// 30 degree cone stops 0.6 m short of the wall); the camera sees only the wall, whose light is
// all the floor's bounce, carried by photons.
std::vector<float> wall(bool qmc, uint64_t seed) {
    SceneDesc s = lp::empty_scene({-1.5f, 0, 0.5f}, {1, 0, 0.5f}, {0, 0, 1}, 20, 16);
    const int white = lp::add_material(s, MaterialType::Diffuse, Vec3(0.8f));
    lp::add_quad(s, {-3, -3, 0}, {6, 0, 0}, {0, 6, 0}, white);
    lp::add_quad(s, {1, -3, 0}, {0, 6, 0}, {0, 0, 3}, white);
    lp::add_spot(s, {-0.5f, 0, 1.5f}, {0, 0, -1}, 30, 100);
    return lp::steady_image(s, 2, 8, 20000, seed, [&](RenderContext& ctx) { ctx.photon_qmc = qmc; });
}

TEST(PhotonQmc, TheFloorsBounceOnAWallVariesLessFromSeedToSeedWithTheSameMean) {
    const int seeds = 24;
    double mean[2] = {0, 0}, sd[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
        std::vector<double> m;
        for (int s = 1; s <= seeds; ++s) {
            const std::vector<float> img = wall(k == 1, static_cast<uint64_t>(s));
            double sum = 0;
            for (float v : img) sum += v;
            m.push_back(sum / static_cast<double>(img.size()));
        }
        for (double v : m) mean[k] += v / seeds;
        for (double v : m) sd[k] += (v - mean[k]) * (v - mean[k]) / (seeds - 1);
        sd[k] = std::sqrt(sd[k]);
    }
    std::printf("image mean over %d seeds: independent %.5f sd %.5f; Halton %.5f sd %.5f (%.2fx less)\n", seeds,
                mean[0], sd[0], mean[1], sd[1], sd[0] / sd[1]);
    // The same mean within the two means' combined standard error, times 4.
    EXPECT_NEAR(mean[1], mean[0], 4 * std::sqrt((sd[0] * sd[0] + sd[1] * sd[1]) / seeds));
    // 24 seeds estimate each spread to about 15 %: equal spreads would pass this about 1 time
    // in 70 (the F distribution of 23 and 23 degrees of freedom above 1.6 squared).
    EXPECT_GT(sd[0], 1.6 * sd[1]);
}

}  // namespace
}  // namespace sl
