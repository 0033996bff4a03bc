// Arrivals at t = start, exactly on bucket edges, at t = end and beyond, through the whole
// renderer (camera pass, photon pass, gather, frame assembly), not only through Timeline.
//
// An emitter seen directly arrives at exactly t = 0 (without camera_tof), so moving the
// timeline around 0 puts a known, exact arrival on a start, an edge, the end, or past it.
// Random arrivals (direct light and photons in a closed box) are then checked between two
// timelines whose frame edges coincide exactly: same frames, bit for bit.
#include <cmath>

#include "hard_helpers.h"

namespace sl::hard {
namespace {

// A camera that sees nothing but the front of a quad light of radiance (1, 2, 3).
SceneDesc emitter_only(double start, double end, int frames, EmissionMode mode, double pulse_ns = 0) {
    SceneDesc s;
    s.source = "<hard: emitter>";
    s.camera.position = {0, 0, 3};
    s.camera.look_at = {0, 0, 0};
    s.camera.vfov_deg = 20;  // sees +-0.53 m of the 2 m light
    s.camera.width = s.camera.height = 6;
    s.materials = {diffuse("grey", 0.5f)};
    LightDesc l;
    l.type = LightType::Quad;
    l.corner = {-1, -1, 0};
    l.edge1 = {2, 0, 0};
    l.edge2 = {0, 2, 0};  // faces +z, the camera
    l.radiance = {1, 2, 3};
    s.lights = {l};
    s.time = {start, end, frames, 24};
    s.emission.mode = mode;
    s.emission.width_ns = pulse_ns;
    s.emission.width_frames = pulse_ns > 0 ? static_cast<int>(std::lround(pulse_ns / timeline_of(s).delta())) : 1;
    s.render.passes = 3;
    s.render.photons_per_pass = 100;
    return s;
}

// Which frames show the emitter (every pixel must be all or nothing, exactly).
std::vector<int> lit_frames(const Rendered& r) {
    std::vector<int> lit;
    for (size_t k = 0; k < r.frames.size(); ++k) {
        const Image& f = r.frames[k];
        bool on = f[0] == 1.0f && f[1] == 2.0f && f[2] == 3.0f;
        for (size_t i = 0; i < f.size(); i += 3) {
            bool same = on ? (f[i] == 1.0f && f[i + 1] == 2.0f && f[i + 2] == 3.0f)
                           : (f[i] == 0 && f[i + 1] == 0 && f[i + 2] == 0);
            EXPECT_TRUE(same) << "frame " << k << " value " << f[i] << " at " << i / 3;
        }
        if (on) lit.push_back(static_cast<int>(k));
    }
    return lit;
}

void expect_steady_is_emitter(const Rendered& r) {
    for (size_t i = 0; i < r.steady.size(); i += 3) {
        ASSERT_EQ(r.steady[i], 1.0f);
        ASSERT_EQ(r.steady[i + 1], 2.0f);
        ASSERT_EQ(r.steady[i + 2], 3.0f);
    }
}

struct Case {
    const char* what;
    double start, end;
    int frames;
    std::vector<int> constant_lit, pulse_lit;
};

TEST(TimeEdges, AnExactArrivalAtStartOnEdgesAtEndAndBeyond) {
    const std::vector<Case> cases = {
        {"t = start", 0, 1, 4, {0, 1, 2, 3}, {0}},
        {"t on the edge of frame 3", -1.5, 1.5, 6, {3, 4, 5}, {3}},
        {"t on the edge of the last frame", -2.5, 0.5, 6, {5}, {5}},
        {"t = end: no frame", -1, 0, 4, {}, {}},
        {"t beyond the end", -2, -1, 2, {}, {}},
        {"t before start: constant frames have it, pulses not", 1e-9, 1, 4, {0, 1, 2, 3}, {}},
        {"t a hair before start", 1e-300, 1, 4, {0, 1, 2, 3}, {}},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        for (int sections : {1, 2}) {
            Rendered con = render(emitter_only(c.start, c.end, c.frames, EmissionMode::Constant), sections);
            EXPECT_EQ(lit_frames(con), c.constant_lit) << sections << " section(s)";
            expect_steady_is_emitter(con);
            Rendered pul = render(emitter_only(c.start, c.end, c.frames, EmissionMode::Pulse), sections);
            EXPECT_EQ(lit_frames(pul), c.pulse_lit) << sections << " section(s)";
            expect_steady_is_emitter(pul);
        }
        Rendered fbf = render(emitter_only(c.start, c.end, c.frames, EmissionMode::Constant), 1, true);
        EXPECT_EQ(lit_frames(fbf), c.constant_lit) << "frame by frame";
    }
}

TEST(TimeEdges, APulseOfTwoFramesEndsOnTheEdge) {
    // A pulse of width 2Δ shows arrivals in [end of frame - 2Δ, end of frame): t = 0 on the
    // edge of frame 3 is in frames 3 and 4, and with t = start, in frames 0 and 1.
    EXPECT_EQ(lit_frames(render(emitter_only(-1.5, 1.5, 6, EmissionMode::Pulse, 1.0))), (std::vector<int>{3, 4}));
    EXPECT_EQ(lit_frames(render(emitter_only(0, 3, 6, EmissionMode::Pulse, 1.0))), (std::vector<int>{0, 1}));
    EXPECT_EQ(lit_frames(render(emitter_only(-3, 0, 6, EmissionMode::Pulse, 1.0))), (std::vector<int>{}));
}

TEST(TimeEdges, ShiftedTimelinesWithSharedEdgesGiveTheSameFrames) {
    // Direct light and photons in a closed box arrive at all sorts of times. Timelines whose
    // frame edges are the same exact numbers must bucket every arrival the same way, so a
    // short timeline's frames equal the matching frames of a long one bit for bit (pulse), and
    // the long one, covering every arrival, sums to the steady image.
    SceneDesc s = closed_box(10, 4, 3000);
    s.emission.mode = EmissionMode::Pulse;
    s.time = {2, 6, 8, 24};       // frames of 0.5 ns, edges 2, 2.5, ..., 6
    Rendered narrow = render(s);
    s.time = {-0.5, 150, 301, 24};  // the same edges, from before t = 0 to after the longest path
    Rendered wide = render(s);
    ASSERT_EQ(narrow.buffer_non_finite + wide.buffer_non_finite, 0u);
    for (int k = 0; k < 8; ++k) EXPECT_EQ(narrow.frames[k], wide.frames[k + 5]) << "frame " << k;
    double sum = 0;
    for (const Image& f : wide.frames) sum += mean(f);
    EXPECT_NEAR(sum, mean(wide.steady), 1e-5 * mean(wide.steady));
    EXPECT_NEAR(mean(narrow.steady), mean(wide.steady), 1e-5 * mean(wide.steady));
    // No path is longer than max_depth box diagonals (8 x 3.47 m, 92.5 ns): later frames are black.
    for (size_t k = 190; k < wide.frames.size(); ++k) ASSERT_EQ(mean(wide.frames[k]), 0.0) << "frame " << k;
    // Before t = 0 nothing can arrive.
    EXPECT_EQ(mean(wide.frames[0]), 0.0);

    // Constant emission: the same, up to the order of summation.
    s.emission.mode = EmissionMode::Constant;
    s.time = {2, 6, 8, 24};
    Rendered cn = render(s);
    s.time = {-0.5, 150, 301, 24};
    Rendered cw = render(s);
    for (int k = 0; k < 8; ++k)
        for (size_t i = 0; i < cn.frames[k].size(); ++i)
            ASSERT_NEAR(cn.frames[k][i], cw.frames[k + 5][i], 1e-5f * (1 + cw.frames[k + 5][i])) << "frame " << k;
}

}  // namespace
}  // namespace sl::hard
