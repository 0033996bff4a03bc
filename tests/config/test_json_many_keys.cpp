// Parsing is linear in an object's key count: a scene with 300,000 materials (a 17 MB file,
// under the 64 MiB limit) parses, and the strict checks still hold at that size. (nlohmann's
// parser callback rescans the parent object after every nested value, which made this case
// quadratic: 80,000 materials took 45 s and 300,000 did not finish.)
#include <gtest/gtest.h>

#include <string>

#include "config/parse_scene.h"
#include "foundation/errors.h"

namespace sl {
namespace {

std::string scene_with_materials(int n, const std::string& extra_key) {
    std::string text = R"({"camera": {"position": [0, 1, 3], "look_at": [0, 1, 0], "width": 16, "height": 16},
        "lights": [{"type": "point", "position": [0, 1.5, 0], "power": [1, 1, 1]}], "materials": {)";
    text.reserve(static_cast<size_t>(n) * 60);
    for (int i = 0; i < n; ++i)
        text += "\"m" + std::to_string(i) + "\": {\"type\": \"diffuse\", \"albedo\": [0.5, 0.5, 0.5]},";
    text += extra_key + "}}";
    return text;
}

TEST(JsonManyKeys, ThreeHundredThousandMaterialsParse) {
    const int n = 300000;
    SceneDesc s = parse_scene_text(scene_with_materials(n, R"("last": {"type": "mirror"})"), "many.json", "");
    EXPECT_EQ(s.materials.size(), static_cast<size_t>(n) + 1);
}

TEST(JsonManyKeys, DuplicateKeyFoundAmongThousands) {
    try {
        parse_scene_text(scene_with_materials(50000, R"("m123": {"type": "mirror"})"), "many.json", "");
        FAIL() << "a duplicate key was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), "many.json: key 'materials.m123': duplicate key");
    }
}

}  // namespace
}  // namespace sl
