// The scene a newcomer copies from README.md parses as written, and is the shipped sample it
// claims to be (so the README cannot drift from what the program accepts).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "config/parse_scene.h"
#include "tests/test_paths.h"

using namespace sl;

TEST(Readme, TheScenePrintedInItParsesAndIsTheSample) {
    const std::string root = test::source_dir();
    std::ifstream f(root + "/README.md");
    std::stringstream ss;
    ss << f.rdbuf();
    const std::string text = ss.str();
    const size_t section = text.find("## Your own scene");
    ASSERT_NE(section, std::string::npos);
    const size_t begin = text.find("```json\n", section);
    ASSERT_NE(begin, std::string::npos);
    const size_t end = text.find("```", begin + 8);
    const std::string json = text.substr(begin + 8, end - begin - 8);

    SceneDesc s = parse_scene_text(json, "README.md", root + "/samples");
    EXPECT_EQ(s.shapes.size(), 6u);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].type, LightType::Spot);
    EXPECT_EQ(s.shapes.back().type, ShapeType::Mesh);
    EXPECT_TRUE(s.medium.present);

    SceneDesc sample = parse_scene_file(root + "/samples/spot_mesh_haze.json");
    EXPECT_EQ(sample.shapes.size(), s.shapes.size());
    EXPECT_EQ(sample.shapes.back().file, s.shapes.back().file);
    EXPECT_EQ(sample.lights[0].cone_deg, s.lights[0].cone_deg);
    EXPECT_EQ(sample.time.frames, s.time.frames);
}
