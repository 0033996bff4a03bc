// The split of a pass's photon batches among MPI ranks by cost: every batch traced by exactly one
// rank, a split that is already balanced left alone, and an unbalanced one moved, pass after
// pass, to where the ranks' busy times (simulated from a linear cost model) are equal to within
// one batch, the optimum derived here by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "stages/render/batch_shares.h"

namespace sl {
namespace {

constexpr int kBatch = 4096;

void expect_valid(const std::vector<size_t>& bounds, size_t nbatches, int ranks) {
    ASSERT_EQ(bounds.size(), static_cast<size_t>(ranks) + 1);
    EXPECT_EQ(bounds.front(), 0u);
    EXPECT_EQ(bounds.back(), nbatches);
    for (size_t r = 0; r + 1 < bounds.size(); ++r) EXPECT_LE(bounds[r], bounds[r + 1]);
}

// Busy time of every rank under a linear model: fixed work plus a cost per photon path.
std::vector<double> busy(const std::vector<size_t>& bounds, int64_t photons, const std::vector<double>& fixed,
                         const std::vector<double>& cost) {
    std::vector<double> w(fixed.size());
    for (size_t r = 0; r < w.size(); ++r)
        w[r] = fixed[r] + cost[r] * static_cast<double>(photons_in_share(bounds, static_cast<int>(r), photons, kBatch));
    return w;
}

}  // namespace

TEST(BatchShares, EvenSharesCoverEveryBatchOnce) {
    for (size_t nbatches : {size_t(0), size_t(1), size_t(5), size_t(49), size_t(245)})
        for (int ranks : {1, 2, 3, 7, 64}) {
            const std::vector<size_t> b = even_batch_shares(nbatches, ranks);
            expect_valid(b, nbatches, ranks);
            for (int r = 0; r < ranks; ++r) EXPECT_LE(b[r + 1] - b[r], nbatches / ranks + 1);
        }
    // 200,000 photons: 48 batches of 4096 and one of 3392.
    const std::vector<size_t> b = even_batch_shares(49, 2);
    EXPECT_EQ(photons_in_share(b, 0, 200000, kBatch), 24 * 4096);
    EXPECT_EQ(photons_in_share(b, 1, 200000, kBatch), 24 * 4096 + 3392);
}

TEST(BatchShares, BalancedSplitStays) {
    // Equal ranks: the even split leaves rank 1 3392 photons more, and the best whole-batch
    // split (the other is 25 against 23 and a part, 4800 apart) is that one.
    const int64_t photons = 200000;
    const std::vector<double> fixed = {0.1, 0.1}, cost = {1.5e-6, 1.5e-6};
    std::vector<size_t> b = even_batch_shares(49, 2);
    for (int pass = 0; pass < 20; ++pass) {
        b = rebalanced_batch_shares(b, photons, kBatch, busy(b, photons, fixed, cost), cost);
        expect_valid(b, 49, 2);
        EXPECT_EQ(b[1], 24u) << "pass " << pass;
    }
}

TEST(BatchShares, SlowerRankGetsFewerPhotonsUntilBusyTimesMeet) {
    // Rank 1 traces at half the speed of rank 0 (a core shared with another process), both
    // with the same fixed work: equal busy times need n0 c = n1 2c, n0 = 2/3 of the photons.
    const int64_t photons = 200000;
    const std::vector<double> fixed = {0.05, 0.05}, cost = {1e-6, 2e-6};
    std::vector<size_t> b = even_batch_shares(49, 2);
    for (int pass = 0; pass < 12; ++pass) b = rebalanced_batch_shares(b, photons, kBatch, busy(b, photons, fixed, cost), cost);
    expect_valid(b, 49, 2);
    EXPECT_NEAR(static_cast<double>(photons_in_share(b, 0, photons, kBatch)), photons * 2.0 / 3.0, kBatch);
    // One batch moved from one rank to the other changes the difference by (1 + 2) us x 4096.
    const std::vector<double> w = busy(b, photons, fixed, cost);
    EXPECT_LT(std::fabs(w[0] - w[1]), 3e-6 * kBatch);
}

TEST(BatchShares, MoreFixedWorkMeansFewerPhotons) {
    // Three ranks of equal speed; rank 2 has 30 ms more other work (its pixels are the
    // expensive ones): it must end with 30 ms / 1.5 us = 20,000 photons fewer than the others,
    // which share the rest equally: (P + 20,000) / 3 each and (P - 2 x 20,000) / 3 for it.
    const int64_t photons = 1000000;
    const size_t nbatches = (photons + kBatch - 1) / kBatch;
    const std::vector<double> fixed = {0.1, 0.1, 0.13}, cost = {1.5e-6, 1.5e-6, 1.5e-6};
    std::vector<size_t> b = even_batch_shares(nbatches, 3);
    for (int pass = 0; pass < 15; ++pass) b = rebalanced_batch_shares(b, photons, kBatch, busy(b, photons, fixed, cost), cost);
    expect_valid(b, nbatches, 3);
    EXPECT_NEAR(static_cast<double>(photons_in_share(b, 2, photons, kBatch)), (photons - 2 * 20000) / 3.0, 1.5 * kBatch);
    EXPECT_NEAR(static_cast<double>(photons_in_share(b, 0, photons, kBatch)), (photons + 20000) / 3.0, 1.5 * kBatch);
}

TEST(BatchShares, RankWithoutBatchesGetsThemBackAndBadTimingsChangeNothing) {
    const int64_t photons = 40000;  // 10 batches
    const std::vector<size_t> starved = {0, 0, 10};
    // Rank 0 traced nothing (no cost of its own) and was idle most of the pass.
    std::vector<size_t> b = rebalanced_batch_shares(starved, photons, kBatch, {0.01, 0.08}, {0.0, 1e-6});
    expect_valid(b, 10, 2);
    EXPECT_GT(b[1], 0u);
    const std::vector<size_t> even = even_batch_shares(10, 2);
    EXPECT_EQ(rebalanced_batch_shares(even, photons, kBatch, {0.0, 0.1}, {1e-6, 1e-6}), even);
    EXPECT_EQ(rebalanced_batch_shares(even, photons, kBatch, {NAN, 0.1}, {1e-6, 1e-6}), even);
    EXPECT_EQ(rebalanced_batch_shares(even, photons, kBatch, {0.1, 0.1}, {0.0, 0.0}), even);
    EXPECT_EQ(rebalanced_batch_shares({0, 10}, photons, kBatch, {0.1}, {1e-6}), (std::vector<size_t>{0, 10}));
}

}  // namespace sl
