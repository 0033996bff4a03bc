// Every shipped sample and the built-in default scene parse.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "config/default_scene.h"
#include "config/parse_scene.h"
#include "tests/test_paths.h"

namespace fs = std::filesystem;
using namespace sl;

TEST(Samples, EverySampleParses) {
    int count = 0;
    for (const auto& entry : fs::directory_iterator(fs::path(test::source_dir()) / "samples")) {
        if (entry.path().extension() != ".json") continue;
        SCOPED_TRACE(entry.path().string());
        SceneDesc s;
        ASSERT_NO_THROW(s = parse_scene_file(entry.path().string()));
        // Lights of its own, or files that bring theirs (checked when they are read: core/import).
        bool imports = false;
        for (const ShapeDesc& sh : s.shapes) imports |= sh.material < 0;
        EXPECT_TRUE(!s.lights.empty() || imports);
        EXPECT_EQ(s.source, entry.path().string());
        ++count;
    }
    EXPECT_GE(count, 3);
}

TEST(Samples, DefaultSceneIsTheCornellBox) {
    SceneDesc d = parse_default_scene();
    SceneDesc c = parse_scene_file(std::string(test::source_dir()) + "/samples/cornell_box.json");
    EXPECT_EQ(d.source, "<default>");
    EXPECT_EQ(d.shapes.size(), c.shapes.size());
    EXPECT_EQ(d.materials.size(), c.materials.size());
    EXPECT_EQ(d.time.frames, c.time.frames);
    EXPECT_EQ(d.render.photons_per_pass, c.render.photons_per_pass);
    EXPECT_EQ(d.emission.mode, EmissionMode::Constant);
}

TEST(Samples, PulseCornellBoxDiffersOnlyInEmission) {
    std::string dir = std::string(test::source_dir()) + "/samples/";
    SceneDesc c = parse_scene_file(dir + "cornell_box.json");
    SceneDesc p = parse_scene_file(dir + "cornell_box_pulse.json");
    EXPECT_EQ(p.emission.mode, EmissionMode::Pulse);
    EXPECT_EQ(p.emission.width_frames, 1);
    EXPECT_EQ(p.shapes.size(), c.shapes.size());
    EXPECT_EQ(p.time.end_ns, c.time.end_ns);
}

TEST(Samples, Corridor) {
    SceneDesc s = parse_scene_file(std::string(test::source_dir()) + "/samples/corridor.json");
    EXPECT_EQ(s.camera.width, 256);
    EXPECT_EQ(s.camera.height, 144);
    EXPECT_EQ(s.render.passes, 32);
    EXPECT_EQ(s.render.photons_per_pass, 100000);
    EXPECT_EQ(s.time.end_ns - s.time.start_ns, 60);
}
