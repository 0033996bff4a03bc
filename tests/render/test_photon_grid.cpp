// The photon grid: a pass's records counting-sorted into hash cells (PhotonMap). A gather must
// visit exactly the records within its radius, checked here against a brute-force scan of the
// same records; and the grid's order must be the same whatever number of threads sorted it,
// since every pixel's sums follow that order and renders on any thread or rank count are the
// same, bit for bit.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "scenes_for_tests.h"
#include "stages/render/photon_map.h"

namespace sl {
namespace {

constexpr double kCell = 0.2;  // grid cells: twice the largest gather radius
constexpr float kRadius = 0.1f;

void build(PhotonMap& map, const RenderContext& ctx, int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
    const SectionLayout layout = make_section(ctx.timeline, ctx.scene.emission.mode, 1, 0);
    PhotonTraceCounters counters;
    ASSERT_TRUE(map.build(ctx, layout, 3, ctx.scene.render.photons_per_pass, kCell, counters));
}

TEST(PhotonGrid, AGatherVisitsExactlyTheRecordsWithinItsRadius) {
    RenderContext ctx(test::small_box(8, 1, 40000));
    PhotonMap map;
    build(map, ctx, 2);
    const std::span<const PhotonRecord> all = map.records();
    ASSERT_GT(all.size(), 40000u);  // several records per path in the closed box
    const float r2 = kRadius * kRadius;
    size_t queries = 0, found_total = 0;
    // Around recorded points (where the gathers find something) and on a lattice through the box.
    std::vector<Vec3> at;
    for (size_t i = 0; i < all.size(); i += 211) at.push_back({all[i].x + 0.03f, all[i].y - 0.02f, all[i].z});
    for (float x = -0.95f; x < 1; x += 0.3f)
        for (float y = 0.05f; y < 2; y += 0.3f) at.push_back({x, y, 0.95f - y * 0.9f});
    for (const Vec3& p : at) {
        std::vector<const PhotonRecord*> gathered, scanned;
        map.for_each_near(p.x, p.y, p.z, r2, [&](const PhotonRecord& rec) { gathered.push_back(&rec); });
        for (const PhotonRecord& rec : all) {
            const float dx = rec.x - p.x, dy = rec.y - p.y, dz = rec.z - p.z;
            if (dx * dx + dy * dy + dz * dz < r2) scanned.push_back(&rec);
        }
        std::sort(gathered.begin(), gathered.end());
        ASSERT_EQ(gathered, scanned) << "at (" << p.x << ", " << p.y << ", " << p.z << ")";  // each once
        ++queries;
        found_total += scanned.size();
    }
    EXPECT_GT(found_total, 10 * queries);  // the gathers were not trivially empty
}

TEST(PhotonGrid, TheGridOrderIsTheSameOnOneAndOnTwoThreads) {
    RenderContext ctx(test::small_box(8, 1, 40000));
    PhotonMap one, two;
    build(one, ctx, 1);
    build(two, ctx, 2);
    ASSERT_EQ(one.size(), two.size());
    ASSERT_GT(one.size(), 40000u);
    EXPECT_EQ(std::memcmp(one.records().data(), two.records().data(), one.size() * sizeof(PhotonRecord)), 0);
    // Built again into the same map (its buffers kept from the last pass): the same order again.
    build(two, ctx, 1);
    ASSERT_EQ(one.size(), two.size());
    EXPECT_EQ(std::memcmp(one.records().data(), two.records().data(), one.size() * sizeof(PhotonRecord)), 0);
}

}  // namespace
}  // namespace sl
