// The pixels dealt to MPI ranks: every pixel of the image belongs to exactly one rank, each
// rank's pixels are whole tiles in image order, and shares differ by at most one tile.
#include <gtest/gtest.h>

#include <vector>

#include "stages/render/rank_exchange.h"
#include "stages/render/section_buffer.h"

namespace sl {

TEST(PixelShare, EveryPixelOnceInTilesOfTheBuffer) {
    for (size_t total : {size_t(1), size_t(15), size_t(16), size_t(17), size_t(40 * 24), size_t(1001)}) {
        for (int ranks : {1, 2, 3, 7, 64}) {
            std::vector<int> owner(total, -1);
            size_t counted = 0, most = 0, least = total;
            for (int r = 0; r < ranks; ++r) {
                const PixelShare s{r, ranks, total};
                counted += s.count();
                most = std::max(most, s.count());
                least = std::min(least, s.count());
                size_t previous = 0;
                for (size_t i = 0; i < s.count(); ++i) {
                    const size_t g = s.global(i);
                    ASSERT_LT(g, total);
                    EXPECT_EQ(owner[g], -1) << "pixel " << g << " dealt twice";
                    owner[g] = r;
                    if (i > 0) {
                        EXPECT_GT(g, previous);  // image order
                    }
                    previous = g;
                    // A buffer tile (16 local pixels) is one image tile.
                    EXPECT_EQ(g / SectionBuffer::kTile, s.global(i - i % PixelShare::kTile) / SectionBuffer::kTile);
                }
            }
            EXPECT_EQ(counted, total) << total << " pixels on " << ranks << " ranks";
            for (size_t p = 0; p < total; ++p) EXPECT_GE(owner[p], 0) << "pixel " << p << " of nobody";
            EXPECT_LE(most - least, PixelShare::kTile);
        }
    }
}

TEST(PixelShare, OneRankIsTheWholeImage) {
    const PixelShare s{0, 1, 1001};
    ASSERT_EQ(s.count(), 1001u);
    for (size_t i = 0; i < s.count(); ++i) ASSERT_EQ(s.global(i), i);
}

}  // namespace sl
