// Arrival times on bucket edges, at start, at end and beyond land where docs/scene-format.md says.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <limits>
#include <vector>

#include "foundation/timeline.h"
#include "stages/render/section_layout.h"

namespace sl {
namespace {

TEST(Timeline, EdgesBelongToTheLaterBucket) {
    for (double start : {0.0, -3.0, 1e-3, 7.25, 1e4}) {
        for (double span : {1.0, 12.0, 0.3, 1e-3, 33333.0}) {
            for (int frames : {1, 3, 10, 48, 192}) {
                Timeline tl{start, start + span, frames};
                for (int k = 0; k <= frames; ++k) {
                    double e = tl.edge(k);
                    ASSERT_EQ(tl.bucket(e), k) << start << " " << span << " " << frames << " k=" << k;
                    ASSERT_EQ(tl.bucket(std::nextafter(e, -1e300)), k - 1);
                }
            }
        }
    }
}

TEST(Timeline, StartEndAndBeyond) {
    Timeline tl{2.0, 14.0, 48};
    EXPECT_EQ(tl.bucket(2.0), 0);       // t = start: the first frame
    EXPECT_EQ(tl.bucket(14.0), 48);     // t = end: no frame, only steady.exr
    EXPECT_GE(tl.bucket(1e6), 48);
    EXPECT_LT(tl.bucket(1.999), 0);
    EXPECT_LT(tl.bucket(-1e300), 0);
    EXPECT_GE(tl.bucket(std::numeric_limits<double>::infinity()), 48);
    EXPECT_GE(tl.bucket(std::nan("")), 48);  // never a frame
}

TEST(Timeline, PicosecondBinsInAHundredMeterScene) {
    // Path lengths are kept in double: 1 ps bins stay exact at ~333 ns (100 m of light).
    Timeline tl{0.0, 400.0, 400000};
    for (int k = 333000; k < 333100; ++k) {
        double mid = (k + 0.5) * 1e-3;
        EXPECT_EQ(tl.bucket(mid), k);
    }
}

TEST(SectionLayout, SlotsCoverBeforeFramesAndAfterWhereNeeded) {
    Timeline tl{0, 12, 48};
    // Constant emission from t = 0: the first section has nothing earlier, the middle ones
    // keep a "before" slot, the last one "before" and "after" (steady.exr): extras 0, 1, 1, 2,
    // so 13, 12, 12, 11 frames give every section 13 slots.
    std::vector<SectionLayout> c = make_sections(tl, EmissionMode::Constant, 4);
    ASSERT_EQ(c.size(), 4u);
    const int frames[] = {13, 12, 12, 11};
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(c[k].frames(), frames[k]) << k;
        EXPECT_EQ(c[k].slots(), 13) << k;
        EXPECT_EQ(c[k].full_paths, k == 3);
        EXPECT_EQ(c[k].has_before, k > 0);
        EXPECT_EQ(c[k].has_after, k == 3);
    }
    const SectionLayout& s = c[1];  // frames 13..24
    EXPECT_EQ(s.first_frame, 13);
    EXPECT_EQ(s.end_frame, 25);
    EXPECT_DOUBLE_EQ(s.cut_ns, 6.25);
    EXPECT_EQ(s.slot_of_bucket(-5), 0);
    EXPECT_EQ(s.slot_of_bucket(12), 0);
    EXPECT_EQ(s.slot_of_bucket(13), 1);
    EXPECT_EQ(s.slot_of_bucket(24), 12);
    EXPECT_EQ(s.slot_of_bucket(25), -1);  // later light: of no use to this section
    EXPECT_EQ(c[0].slot_of_bucket(0), 0);
    EXPECT_EQ(c[0].slot_of_bucket(-1), -1);
    EXPECT_EQ(c[3].slot_of_bucket(48), c[3].after_slot());
    EXPECT_EQ(c[3].after_slot(), 12);

    // A pulse of 3 buckets looks back 2 in every section and needs no "before" but in the last.
    Timeline pulse3 = tl;
    pulse3.pulse_buckets = 3;
    std::vector<SectionLayout> p = make_sections(pulse3, EmissionMode::Pulse, 4);
    EXPECT_EQ(p[1].first_bucket, p[1].first_frame - 2);
    EXPECT_FALSE(p[1].has_before);
    EXPECT_EQ(p[1].slot_of_bucket(p[1].first_bucket), 0);
    EXPECT_EQ(p[1].slot_of_bucket(p[1].first_bucket - 1), -1);
    EXPECT_TRUE(p[3].has_before && p[3].has_after);
    EXPECT_EQ(max_section_slots(pulse3, EmissionMode::Pulse, 4), 15);

    // A timeline that starts after t = 0: the first section does see earlier light.
    EXPECT_TRUE(make_section(Timeline{2, 14, 48}, EmissionMode::Constant, 4, 0).has_before);
}

TEST(SectionLayout, FramesAreSharedSoThatBuffersAreAsEqualAsPossible) {
    for (EmissionMode mode : {EmissionMode::Constant, EmissionMode::Pulse})
        for (int pulse : {1, 4})
            for (int f : {1, 2, 3, 7, 48, 192, 1000})
                for (int k = 1; k <= std::min(f, 40); ++k) {
                    Timeline tl{0, 1, f, pulse};
                    std::vector<SectionLayout> s = make_sections(tl, mode, k);
                    ASSERT_EQ(static_cast<int>(s.size()), k);
                    int next = 0, most = 0, least = 1 << 30;
                    bool any_forced = false;  // a section held at one frame may sit below the rest
                    for (const SectionLayout& l : s) {
                        ASSERT_EQ(l.first_frame, next);
                        ASSERT_GE(l.frames(), 1);
                        next = l.end_frame;
                        most = std::max(most, l.slots());
                        least = std::min(least, l.slots());
                        any_forced |= l.frames() == 1;
                    }
                    ASSERT_EQ(next, f);
                    if (!any_forced) {
                        ASSERT_LE(most - least, 1) << f << " frames, " << k << " sections";
                    }
                    ASSERT_EQ(most, max_section_slots(tl, mode, k));
                    // More sections never need a larger buffer (--max-memory searches on this).
                    if (k > 1) {
                        ASSERT_LE(most, max_section_slots(tl, mode, k - 1));
                    }
                }
}

}  // namespace
}  // namespace sl
