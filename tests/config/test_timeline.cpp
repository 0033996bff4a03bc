// The Timeline is the one place that computes with time: its edges end exactly at end_ns (a
// sum start + k*Δ need not), every edge is the first instant of its own bucket, and its
// whole-frames check is what the parser, the overrides and `retime` all apply to a pulse.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "config/scene_desc.h"
#include "foundation/timeline.h"

using sl::Timeline;

TEST(Timeline, TheLastEdgeIsEndExactly) {
    const Timeline t{0.3, 5.9, 9};
    EXPECT_NE(0.3 + 9 * t.delta(), 5.9);  // why the edges come from one place: the sum rounds
    EXPECT_EQ(t.edge(9), 5.9);
    EXPECT_EQ(t.edge(0), 0.3);
    for (int k = 0; k < 9; ++k) {
        EXPECT_EQ(t.bucket(t.edge(k)), k) << k;  // an edge belongs to the later bucket
        EXPECT_LT(t.edge(k), t.edge(k + 1));
    }
    EXPECT_EQ(t.bucket(5.9), 9);  // end belongs to no frame
}

TEST(Timeline, WholeFramesWithinOnePartPerMillion) {
    const Timeline t{0, 24, 48};  // Δ = 0.5 ns
    EXPECT_EQ(t.whole_frames(1.0), std::optional<double>(2));
    EXPECT_EQ(t.whole_frames(0.5 * (1 + 5e-7)), std::optional<double>(1));
    EXPECT_EQ(t.whole_frames(0.5 * (1 + 2e-6)), std::nullopt);
    EXPECT_EQ(t.whole_frames(0.7), std::nullopt);
    EXPECT_EQ(t.whole_frames(0.25), std::nullopt);  // less than one frame
    EXPECT_TRUE(t.has_valid_delta());
    EXPECT_FALSE((Timeline{-1.7e308, 1.7e308, 1}.has_valid_delta()));  // Δ overflows
    EXPECT_FALSE((Timeline{2, 1, 4}.has_valid_delta()));
}

TEST(Timeline, OfASceneCountsPulseBucketsOnlyForPulses) {
    sl::SceneDesc s;
    s.time = {0, 12, 24, 24};
    s.emission.width_frames = 3;
    EXPECT_EQ(sl::timeline_of(s).pulse_buckets, 1);  // constant emission: one bucket a frame
    s.emission.mode = sl::EmissionMode::Pulse;
    EXPECT_EQ(sl::timeline_of(s).pulse_buckets, 3);
    EXPECT_DOUBLE_EQ(sl::timeline_of(s).delta(), 0.5);
}

// BucketFinder (the gathers' multiplication) must answer what bucket() (the division) does, for
// every time: on and beside every edge, far before the start, at and after the end, NaN and
// infinities, on timelines ordinary, offset, huge, tiny and of one frame.
TEST(Timeline, TheBucketFinderAnswersAsBucketDoes) {
    const Timeline lines[] = {
        {0.0, 10.0, 48, 1},         {3.25, 7.0, 192, 1},     {-5.0, 1e-3, 7, 1},
        {1e6, 1e6 + 1e-3, 1000, 1}, {0.0, 1e9, 3, 1},        {0.0, 1e-9, 1, 1},
        {123.456, 789.012, 997, 1}, {1e12, 1e12 + 5.0, 96, 1}};
    uint64_t state = 12345;
    auto uniform = [&] {  // a fixed stream: the test sees the same times every run
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<double>(state >> 11) * 0x1p-53;
    };
    size_t compared = 0;
    for (const Timeline& tl : lines) {
        const sl::BucketFinder finder(tl);
        std::vector<double> times = {std::nan(""), std::numeric_limits<double>::infinity(),
                                     -std::numeric_limits<double>::infinity(), tl.end_ns, tl.start_ns,
                                     tl.start_ns - 1e30, tl.end_ns + 1e30, -1e300, 1e300};
        for (int k = -3; k <= tl.frames + 3; ++k)
            for (double e : {tl.edge(std::clamp(k, 0, tl.frames)), tl.start_ns + k * tl.delta()}) {
                times.push_back(e);
                times.push_back(std::nextafter(e, -1e308));
                times.push_back(std::nextafter(e, 1e308));
            }
        const double span = tl.end_ns - tl.start_ns;
        for (int i = 0; i < 200000; ++i) times.push_back(tl.start_ns - 2 * span + 5 * span * uniform());
        for (int i = 0; i < 2000; ++i) times.push_back(tl.start_ns - span * std::ldexp(1.0, 30 + i % 40) * uniform());
        for (double t : times) {
            ASSERT_EQ(finder(t), tl.bucket(t)) << "t = " << t << " on [" << tl.start_ns << ", " << tl.end_ns
                                               << "], " << tl.frames << " frames";
            ++compared;
        }
    }
    EXPECT_GT(compared, 1600000u);
}
