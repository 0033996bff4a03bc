// The photon grid's hashes come from one of two places: the tracing tasks, when trace() is told
// the cell size (build() and a single process), or finish() itself (ranks, which trace before
// the radius is known). Both must give the same grid, bit for bit, since every pixel's sums
// follow its order; and a trace hashed for one cell size must not leak into a grid of another.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "scenes_for_tests.h"
#include "stages/render/photon_map.h"

namespace sl {
namespace {

constexpr double kCell = 0.2;

bool same_records(const PhotonMap& a, const PhotonMap& b) {
    return a.size() == b.size() &&
           std::memcmp(a.records().data(), b.records().data(), a.size() * sizeof(PhotonRecord)) == 0;
}

// Records in each cell found by gathering around every record: a grid built for the wrong cell
// size would miss some (its cells would not cover the radius) or be ordered differently.
std::vector<size_t> neighbours(const PhotonMap& map, float r) {
    std::vector<size_t> n;
    for (size_t i = 0; i < map.size(); i += 97) {
        const PhotonRecord& p = map.records()[i];
        size_t c = 0;
        map.for_each_near(p.x, p.y, p.z, r * r, [&](const PhotonRecord&) { ++c; });
        n.push_back(c);
    }
    return n;
}

TEST(PhotonGridHashes, TracingTasksAndFinishHashAlike) {
    RenderContext ctx(test::small_box(8, 1, 30000));
    const SectionLayout layout = make_section(ctx.timeline, ctx.scene.emission.mode, 1, 0);
    const int64_t n = ctx.scene.render.photons_per_pass;
    PhotonTraceCounters counters;
    PhotonMap hinted, plain, other;
    ASSERT_TRUE(hinted.trace(ctx, layout, 2, n, counters, false, nullptr, kCell));
    hinted.finish(ctx, kCell, counters, nullptr);
    ASSERT_TRUE(plain.trace(ctx, layout, 2, n, counters, false));
    plain.finish(ctx, kCell, counters, nullptr);
    ASSERT_GT(plain.size(), 30000u);
    EXPECT_TRUE(same_records(hinted, plain));
    EXPECT_EQ(neighbours(hinted, 0.1f), neighbours(plain, 0.1f));

    // Hashed for cells of 0.05 while tracing, then a grid of 0.2 cells: the hashes are redone.
    ASSERT_TRUE(other.trace(ctx, layout, 2, n, counters, false, nullptr, 0.05));
    other.finish(ctx, kCell, counters, nullptr);
    EXPECT_TRUE(same_records(other, plain));
    EXPECT_EQ(neighbours(other, 0.1f), neighbours(plain, 0.1f));

    // The next pass into the same maps, once hinted and once not: still the same grid.
    ASSERT_TRUE(hinted.trace(ctx, layout, 3, n, counters, false));
    hinted.finish(ctx, kCell, counters, nullptr);
    ASSERT_TRUE(plain.trace(ctx, layout, 3, n, counters, false, nullptr, kCell));
    plain.finish(ctx, kCell, counters, nullptr);
    EXPECT_TRUE(same_records(hinted, plain));
}

}  // namespace
}  // namespace sl
