// Command-line overrides of scene values, re-validated.
#include <gtest/gtest.h>

#include "config/parse_scene.h"
#include "foundation/errors.h"

using namespace sl;

namespace {

// 0..24 ns in 48 frames (Δ = 0.5 ns), pulse 1 ns wide (2 frames).
SceneDesc pulse_scene() {
    return parse_scene_text(R"({
        "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
        "lights": [{"type": "point", "position": [0, 1, 0], "power": [1, 1, 1]}],
        "time": {"start_ns": 0, "end_ns": 24, "frames": 48},
        "emission": {"mode": "pulse", "width_ns": 1}
    })",
                            "o.json", "");
}

std::string error_of(SceneDesc s, const RenderOverrides& o) {
    try {
        apply_overrides(s, o);
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST(Overrides, NothingChangesNothing) {
    SceneDesc s = pulse_scene();
    apply_overrides(s, {});
    EXPECT_EQ(s.time.frames, 48);
    EXPECT_EQ(s.emission.width_frames, 2);
}

TEST(Overrides, ValuesReplaceTheScene) {
    SceneDesc s = pulse_scene();
    RenderOverrides o;
    o.frames = 96;  // Δ = 0.25: the 1 ns pulse is now 4 frames
    o.passes = 3;
    o.width = 320;
    o.height = 200;
    o.photons = 5000;
    o.seed = 99;
    o.camera_tof = true;
    apply_overrides(s, o);
    EXPECT_EQ(s.time.frames, 96);
    EXPECT_EQ(s.emission.width_frames, 4);
    EXPECT_EQ(s.render.passes, 3);
    EXPECT_EQ(s.camera.width, 320);
    EXPECT_EQ(s.camera.height, 200);
    EXPECT_EQ(s.render.photons_per_pass, 5000);
    EXPECT_EQ(s.render.seed, 99u);
    EXPECT_TRUE(s.render.camera_tof);
}

TEST(Overrides, Emission) {
    SceneDesc s = pulse_scene();
    RenderOverrides o;
    o.emission = "constant";
    apply_overrides(s, o);
    EXPECT_EQ(s.emission.mode, EmissionMode::Constant);

    o.emission = "pulse";
    apply_overrides(s, o);
    EXPECT_EQ(s.emission.mode, EmissionMode::Pulse);
    EXPECT_EQ(s.emission.width_ns, 0);
    EXPECT_EQ(s.emission.width_frames, 1);

    o.emission = "pulse:1.5";
    apply_overrides(s, o);
    EXPECT_EQ(s.emission.width_ns, 1.5);
    EXPECT_EQ(s.emission.width_frames, 3);
}

TEST(Overrides, BadValuesNameTheFlag) {
    struct Case {
        RenderOverrides o;
        const char* message;
    };
    auto with = [](auto setter) {
        RenderOverrides o;
        setter(o);
        return o;
    };
    const Case cases[] = {
        {with([](auto& o) { o.frames = 0; }),
         "command line: --frames: must be an integer in 1..100000, got 0"},
        {with([](auto& o) { o.passes = -1; }),
         "command line: --passes: must be an integer in 1..10000000, got -1"},
        {with([](auto& o) { o.width = 16385; }),
         "command line: --width: must be an integer in 1..16384, got 16385"},
        {with([](auto& o) { o.height = 0; }),
         "command line: --height: must be an integer in 1..16384, got 0"},
        {with([](auto& o) { o.photons = 0; }),
         "command line: --photons: must be an integer in 1..1000000000, got 0"},
        {with([](auto& o) { o.frames = 36; }),  // Δ = 2/3 ns: 1 ns is not a multiple
         "command line: --frames: pulse width 1 ns is not a whole multiple of the frame width"},
        {with([](auto& o) { o.emission = "pulse:0.7"; }),
         "command line: --emission: pulse width 0.7 ns is not a whole multiple of the frame width"},
        {with([](auto& o) { o.emission = "flash"; }),
         "command line: --emission: must be constant, pulse or pulse:WIDTH_NS, got 'flash'"},
        {with([](auto& o) { o.emission = "pulse:"; }),
         "command line: --emission: the pulse width must be"},
        {with([](auto& o) { o.emission = "pulse:-1"; }),
         "command line: --emission: the pulse width must be"},
        {with([](auto& o) { o.emission = "pulse:inf"; }),
         "command line: --emission: the pulse width must be"},
        {with([](auto& o) { o.emission = "pulse:1ns"; }),
         "command line: --emission: the pulse width must be"},
    };
    for (const Case& c : cases) {
        std::string m = error_of(pulse_scene(), c.o);
        EXPECT_EQ(m.rfind(c.message, 0), 0u) << m;
    }
}

TEST(Overrides, MaxDepthReplacesTheSceneAndIsChecked) {
    SceneDesc s = pulse_scene();
    EXPECT_EQ(s.render.max_depth, 1000);
    RenderOverrides o;
    o.max_depth = 3;
    apply_overrides(s, o);
    EXPECT_EQ(s.render.max_depth, 3);
    o.max_depth = 1000;
    apply_overrides(s, o);
    EXPECT_EQ(s.render.max_depth, 1000);
    o.max_depth = 0;
    EXPECT_EQ(error_of(pulse_scene(), o), "command line: --max-depth: must be an integer in 1..1000, got 0");
    o.max_depth = 1001;
    EXPECT_EQ(error_of(pulse_scene(), o), "command line: --max-depth: must be an integer in 1..1000, got 1001");
}
