// Valid scenes: values, defaults, units and paths come out as docs/scene-format.md says.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "config/parse_scene.h"
#include "foundation/errors.h"
#include "tests/config/scene_fixture.h"

using namespace sl;
using nlohmann::json;

namespace {

SceneDesc parse_json(const json& j, const std::string& base_dir = "") {
    return parse_scene_text(j.dump(2), "test.json", base_dir);
}

int material_named(const SceneDesc& s, const std::string& name) {
    for (size_t i = 0; i < s.materials.size(); ++i)
        if (s.materials[i].name == name) return static_cast<int>(i);
    return -1;
}

void expect_vec(Vec3 a, Vec3 b, float tol = 1e-6f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

class ParseScene : public test::SceneFolder {};

}  // namespace

TEST_F(ParseScene, FullSceneValues) {
    SceneDesc s = parse_json(test::full_scene(), dir.string());
    EXPECT_EQ(s.source, "test.json");
    expect_vec(s.camera.up, {0, 1, 0});  // normalized
    EXPECT_EQ(s.camera.width, 64);
    ASSERT_EQ(s.materials.size(), 3u);
    ASSERT_EQ(s.shapes.size(), 4u);
    EXPECT_EQ(s.shapes[0].type, ShapeType::Quad);
    EXPECT_EQ(s.shapes[0].material, material_named(s, "white"));
    EXPECT_EQ(s.shapes[1].material, material_named(s, "mirror"));
    EXPECT_EQ(s.shapes[2].material, material_named(s, "glass"));
    EXPECT_EQ(s.materials[material_named(s, "glass")].type, MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(s.materials[material_named(s, "glass")].ior, 1.5f);
    EXPECT_EQ(s.shapes[3].file, (dir / "meshes" / "thing.obj").string());
    EXPECT_TRUE(std::filesystem::path(s.shapes[3].file).is_absolute());
    expect_vec(s.shapes[3].rotate_deg, {0, 90, 0});
    ASSERT_EQ(s.lights.size(), 4u);
    EXPECT_EQ(s.lights[2].type, LightType::Spot);
    expect_vec(s.lights[2].direction, {0, -1, 0});
    EXPECT_FLOAT_EQ(s.lights[2].cone_deg, 20);
    EXPECT_TRUE(s.medium.present);
    expect_vec(s.medium.sigma_a, Vec3(0.01f));
    EXPECT_FLOAT_EQ(s.medium.g, 0.3f);
    EXPECT_TRUE(s.medium.has_bounds);
    EXPECT_EQ(s.emission.mode, EmissionMode::Pulse);
    EXPECT_DOUBLE_EQ(s.emission.width_ns, 1);
    EXPECT_EQ(s.emission.width_frames, 2);
    EXPECT_DOUBLE_EQ(timeline_of(s).delta(), 0.5);
    EXPECT_EQ(s.render.passes, 16);
    EXPECT_TRUE(s.render.camera_tof);
    EXPECT_EQ(s.render.seed, 7u);
    expect_vec(s.render.ambient, Vec3(0.1f));
}

TEST(ParseSceneDefaults, MinimalScene) {
    SceneDesc s = parse_scene_text(R"({
        "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
        "lights": [{"type": "point", "position": [0, 1, 0], "power": [1, 1, 1]}]
    })",
                                   "min.json", "");
    const SceneDesc d;  // the documented defaults
    EXPECT_TRUE(s.shapes.empty());
    EXPECT_TRUE(s.materials.empty());
    EXPECT_FALSE(s.medium.present);
    EXPECT_EQ(s.camera.width, d.camera.width);
    EXPECT_EQ(s.camera.height, d.camera.height);
    EXPECT_EQ(s.camera.vfov_deg, d.camera.vfov_deg);
    EXPECT_EQ(s.time.frames, d.time.frames);
    EXPECT_EQ(s.time.end_ns, d.time.end_ns);
    EXPECT_EQ(s.emission.mode, EmissionMode::Constant);
    EXPECT_EQ(s.emission.width_frames, 1);
    EXPECT_EQ(s.render.passes, d.render.passes);
    EXPECT_EQ(s.render.radius, 0);  // automatic
    EXPECT_EQ(s.meters_per_unit, 1);
}

TEST(ParseSceneDefaults, PulseWithoutWidthIsOneFrame) {
    SceneDesc s = parse_scene_text(R"({
        "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
        "lights": [{"type": "point", "position": [0, 1, 0], "power": [1, 1, 1]}],
        "time": {"start_ns": 2, "end_ns": 5, "frames": 30},
        "emission": {"mode": "pulse"}
    })",
                                   "p.json", "");
    EXPECT_EQ(s.emission.width_ns, 0);
    EXPECT_EQ(s.emission.width_frames, 1);
    EXPECT_DOUBLE_EQ(timeline_of(s).delta(), 0.1);
}

TEST(ParseSceneValues, IntegersWrittenAsFloatsAndLargeSeeds) {
    json j = test::full_scene();
    j.erase("shapes");
    j["render"]["photons_per_pass"] = 1e5;
    j["render"]["seed"] = 18446744073709551615ull;
    SceneDesc s = parse_json(j);
    EXPECT_EQ(s.render.photons_per_pass, 100000);
    EXPECT_EQ(s.render.seed, 18446744073709551615ull);
}

TEST(ParseSceneValues, PulseWidthWithinToleranceOfAMultiple) {
    json j = test::full_scene();
    j.erase("shapes");
    j["time"] = {{"start_ns", 0}, {"end_ns", 1}, {"frames", 3}};  // Δ = 1/3, not exact in binary
    j["emission"]["width_ns"] = 0.6666667;                        // 2Δ within 1e-6
    EXPECT_EQ(parse_json(j).emission.width_frames, 2);
}

TEST_F(ParseScene, UnitsScaleLengthsAndCoefficients) {
    json j = test::full_scene();
    j["units"]["meters_per_unit"] = 0.01;  // the file is in centimeters
    j["camera"]["position"] = {0, 100, 350};
    j["camera"]["look_at"] = {0, 100, 0};
    j["shapes"][0] = {{"type", "quad"},
                      {"corner", {-100, 0, 100}},
                      {"edge1", {200, 0, 0}},
                      {"edge2", {0, 0, -200}},
                      {"material", "white"}};
    j["shapes"][1]["min"] = {-50, 0, -50};
    j["shapes"][1]["max"] = {50, 100, 50};
    j["shapes"][2]["center"] = {0, 150, 0};
    j["shapes"][2]["radius"] = 30;
    j["shapes"][3]["translate"] = {100, 0, 0};
    j["shapes"][3]["scale"] = 2;
    j["lights"][0]["position"] = {0, 190, 0};
    j["lights"][3]["radius"] = 0.2;
    j["medium"]["sigma_a"] = 0.0001;  // per cm
    j["medium"]["sigma_s"] = {0.001, 0.002, 0.003};
    j["medium"]["bounds"]["max"] = {100, 200, 100};
    j["render"]["radius"] = 2;
    SceneDesc s = parse_json(j, dir.string());

    EXPECT_DOUBLE_EQ(s.meters_per_unit, 0.01);
    expect_vec(s.camera.position, {0, 1, 3.5f});
    expect_vec(s.camera.look_at, {0, 1, 0});
    expect_vec(s.camera.up, {0, 1, 0});  // a direction: normalized, not scaled
    expect_vec(s.shapes[0].corner, {-1, 0, 1});
    expect_vec(s.shapes[0].edge1, {2, 0, 0});
    expect_vec(s.shapes[1].max, {0.5f, 1, 0.5f});
    expect_vec(s.shapes[2].center, {0, 1.5f, 0});
    EXPECT_FLOAT_EQ(s.shapes[2].radius, 0.3f);
    expect_vec(s.shapes[3].translate, {1, 0, 0});
    EXPECT_FLOAT_EQ(s.shapes[3].scale, 0.02f);       // OBJ coordinates are in the file's units too
    expect_vec(s.shapes[3].rotate_deg, {0, 90, 0});  // angles are not lengths
    expect_vec(s.lights[0].position, {0, 1.9f, 0});
    expect_vec(s.lights[0].power, Vec3(10));        // power unchanged
    expect_vec(s.lights[1].radiance, {17, 12, 4});  // radiance unchanged
    expect_vec(s.lights[1].edge1, {0.005f, 0, 0});  // (written as 0.5 cm)
    expect_vec(s.lights[2].direction, {0, -1, 0});
    EXPECT_FLOAT_EQ(s.lights[3].radius, 0.002f);
    expect_vec(s.medium.sigma_a, Vec3(0.01f), 1e-7f);  // per meter
    expect_vec(s.medium.sigma_s, {0.1f, 0.2f, 0.3f}, 1e-6f);
    expect_vec(s.medium.bounds_max, {1, 2, 1});
    EXPECT_FLOAT_EQ(s.render.radius, 0.02f);
    expect_vec(s.render.ambient, Vec3(0.1f));  // radiance unchanged
    EXPECT_FLOAT_EQ(s.shapes[3].scale, 0.02f);
}

TEST_F(ParseScene, MeshScaleDefaultsToTheUnits) {
    json j = test::full_scene();
    j["units"]["meters_per_unit"] = 0.001;
    j["shapes"][3].erase("scale");
    j["lights"][1]["edge1"] = {500, 0, 0};
    j["lights"][1]["edge2"] = {0, 0, 400};
    EXPECT_FLOAT_EQ(parse_json(j, dir.string()).shapes[3].scale, 0.001f);
}

TEST_F(ParseScene, FileReadsAndResolvesMeshesNextToIt) {
    std::filesystem::path file = dir / "scene.json";
    std::ofstream(file) << test::full_scene().dump();
    SceneDesc s = parse_scene_file(file.string());
    EXPECT_EQ(s.source, file.string());
    EXPECT_EQ(s.shapes[3].file, (dir / "meshes" / "thing.obj").string());
}

TEST_F(ParseScene, AbsoluteMeshPathIsKept) {
    json j = test::full_scene();
    j["shapes"][3]["file"] = (dir / "meshes" / "thing.obj").string();
    EXPECT_EQ(parse_json(j, "/nonexistent").shapes[3].file,
              (dir / "meshes" / "thing.obj").string());
}

TEST_F(ParseScene, UnreadableFiles) {
    auto message = [](const std::string& path) {
        try {
            parse_scene_file(path);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    std::string missing = (dir / "nope.json").string();
    EXPECT_EQ(message(missing).rfind(missing + ": cannot open the scene file", 0), 0u)
        << message(missing);
    EXPECT_EQ(message(dir.string()), dir.string() + ": is a directory, not a scene file");
    std::filesystem::path empty = dir / "empty.json";
    std::ofstream(empty).flush();
    EXPECT_EQ(
        message(empty.string()).rfind(empty.string() + ": line 1, column 1: JSON syntax error", 0),
        0u)
        << message(empty.string());
}
