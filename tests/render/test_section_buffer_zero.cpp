// A new section buffer's accumulators start at zero, in both of its allocator's paths: small
// buffers come from the heap (where a freed buffer's sums may still lie), large ones from a
// fresh mapping, and neither is filled by std::vector (the allocator hands out zeroed memory).
// Every image is the running sum from these zeros, so one stale value would show in every frame.
#include <gtest/gtest.h>

#include <algorithm>

#include "tests/render/section_layout_fixture.h"
#include "stages/render/section_buffer.h"

namespace sl {
namespace {

using test::whole_layout;

size_t nonzero(const SectionBuffer& b) {
    return static_cast<size_t>(std::count_if(b.accum.begin(), b.accum.end(), [](float v) { return v != 0.0f; }));
}

TEST(SectionBufferZero, SmallAndLargeBuffersStartAtZeroAfterAFilledOneIsFreed) {
    // 40 x 30 pixels x 4 slots: 58 KB, the heap path. 300 x 250 x 12 slots: 10.8 MB, the mapping.
    for (auto [pixels, frames] : {std::pair<size_t, int>{40 * 30, 2}, {300 * 250, 10}}) {
        for (int round = 0; round < 3; ++round) {
            auto b = std::make_unique<SectionBuffer>(pixels, whole_layout(frames), 0.01f, false);
            ASSERT_EQ(b->accum.size(), SectionBuffer::padded(pixels) * static_cast<size_t>(frames + 2) * 3);
            EXPECT_EQ(nonzero(*b), 0u) << pixels << " pixels, round " << round;
            std::fill(b->accum.begin(), b->accum.end(), 1.5f);  // what the next buffer must not see
            EXPECT_EQ(nonzero(*b), b->accum.size());
        }
    }
}

}  // namespace
}  // namespace sl
