// Arrival times on bucket edges, at start, at end and beyond land where the contract says.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/timeline.h"
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

TEST(SectionLayout, SlotsCoverBeforeFramesAndAfter) {
    Timeline tl{0, 12, 48};
    SectionLayout s = make_section(tl, 1, 4, 1);  // frames 12..23
    EXPECT_EQ(s.first_frame, 12);
    EXPECT_EQ(s.end_frame, 24);
    EXPECT_FALSE(s.full_paths);
    EXPECT_DOUBLE_EQ(s.cut_ns, 6.0);
    EXPECT_EQ(s.slot_of_bucket(-5), 0);
    EXPECT_EQ(s.slot_of_bucket(11), 0);
    EXPECT_EQ(s.slot_of_bucket(12), 1);
    EXPECT_EQ(s.slot_of_bucket(23), 12);
    EXPECT_EQ(s.slot_of_bucket(24), s.after_slot());
    SectionLayout pulse = make_section(tl, 3, 4, 1);  // a pulse of 3 buckets looks back 2
    EXPECT_EQ(pulse.first_bucket, 10);
    EXPECT_EQ(pulse.slot_of_bucket(10), 1);
    EXPECT_TRUE(make_section(tl, 1, 4, 3).full_paths);
}

}  // namespace
}  // namespace sl
