// The Timeline is the one place that computes with time: its edges end exactly at end_ns (a
// sum start + k*Δ need not), every edge is the first instant of its own bucket, and its
// whole-frames check is what the parser, the overrides and `retime` all apply to a pulse.
#include <gtest/gtest.h>

#include <optional>

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
