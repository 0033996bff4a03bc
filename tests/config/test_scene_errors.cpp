// Bad scenes: each gives one InputError line naming the file and the key at fault.
#include <gtest/gtest.h>

#include "config/parse_scene.h"
#include "foundation/errors.h"
#include "tests/config/scene_fixture.h"

using namespace sl;
using nlohmann::json;

namespace {

// The error message for `text`, or "no error".
std::string error_of(const std::string& text, const std::string& base_dir) {
    try {
        parse_scene_text(text, "bad.json", base_dir);
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

// One edit of the full scene: set the JSON pointer to a value (JSON text), or remove it.
struct BadCase {
    const char* pointer;
    const char* value;  // nullptr: remove the key
    const char* key;    // the key path the message must name
    const char* what;   // a fragment of the message
};

const BadCase kBadCases[] = {
    // top level and sections
    {"/colour", "1", "colour", "unknown key"},
    {"/camera", nullptr, "camera", "required key is missing"},
    {"/camera", "\"front\"", "camera", "must be a JSON object"},
    {"/lights", nullptr, "lights", "required key is missing"},
    {"/lights", "[]", "lights", "at least one light"},
    {"/lights", "{}", "lights", "must be an array"},
    {"/shapes", "{}", "shapes", "must be an array"},
    {"/time", "[0, 1]", "time", "must be a JSON object"},
    // units
    {"/units/meters_per_unit", "0", "units.meters_per_unit", "must be a finite number > 0, got 0"},
    {"/units/meters_per_unit", "-1", "units.meters_per_unit", "> 0"},
    {"/units/meters_per_unit", "\"cm\"", "units.meters_per_unit", "got \"cm\""},
    {"/units/scale", "1", "units.scale", "unknown key"},
    {"/units/meters_per_unit", "1e12", "camera.position", "lengths must be within"},
    // camera
    {"/camera/width", "0", "camera.width", "must be an integer in 1..16384, got 0"},
    {"/camera/height", "16385", "camera.height", "1..16384"},
    {"/camera/width", "2.5", "camera.width", "integer"},
    {"/camera/width", "\"64\"", "camera.width", "integer"},
    {"/camera/vfov_deg", "180", "camera.vfov_deg", "in (0, 180)"},
    {"/camera/vfov_deg", "0", "camera.vfov_deg", "in (0, 180)"},
    {"/camera/vfov_deg", "179.99999999999", "camera.vfov_deg", "single precision"},
    {"/camera/position", "[0, 1]", "camera.position", "array of 3"},
    {"/camera/position", "[0, 1, \"2\"]", "camera.position", "array of 3"},
    {"/camera/position", "[0, 1, 1e10]", "camera.position", "within"},
    {"/camera/position", nullptr, "camera.position", "required key is missing"},
    {"/camera/look_at", "[0, 1, 3.5]", "camera.look_at", "must differ"},
    {"/camera/up", "[0, 0, 1]", "camera.up", "parallel"},
    {"/camera/up", "[0, 0, 0]", "camera.up", "non-zero"},
    {"/camera/fov", "40", "camera.fov", "unknown key"},
    // materials
    {"/materials/white/type", "\"lambert\"", "materials.white.type", "must be one of"},
    {"/materials/white/type", nullptr, "materials.white.type", "required key is missing"},
    {"/materials/white/albedo", "[1.2, 0, 0]", "materials.white.albedo", "[0, 1]"},
    {"/materials/white/albedo", "[-0.1, 0, 0]", "materials.white.albedo", "[0, 1]"},
    {"/materials/white/albedo", "0.5", "materials.white.albedo", "array of 3"},
    {"/materials/white/ior", "1.5", "materials.white.ior", "unknown key"},
    {"/materials/mirror/reflectance", "[0.5, 0.5, 2]", "materials.mirror.reflectance", "[0, 1]"},
    {"/materials/glass/ior", "0", "materials.glass.ior", "> 0"},
    {"/materials/glass/ior", "-1.5", "materials.glass.ior", "> 0"},
    {"/materials/glass/albedo", "[1, 1, 1]", "materials.glass.albedo", "unknown key"},
    {"/materials/plastic", "5", "materials.plastic", "must be a JSON object"},
    {"/materials", "[]", "materials", "must be a JSON object"},
    // shapes
    {"/shapes/0/material", "\"nope\"", "shapes[0].material", "no material named \"nope\""},
    {"/shapes/0/material", nullptr, "shapes[0].material", "required key is missing"},
    {"/shapes/0/material", "3", "shapes[0].material", "must be a string"},
    {"/shapes/0/type", "\"disk\"", "shapes[0].type", "must be one of"},
    {"/shapes/0/type", nullptr, "shapes[0].type", "required key is missing"},
    {"/shapes/0/edge2", "[4, 0, 0]", "shapes[0].edge2", "zero area"},
    {"/shapes/0/edge1", "[0, 0, 0]", "shapes[0].edge2", "zero area"},
    {"/shapes/0/edge1", nullptr, "shapes[0].edge1", "required key is missing"},
    {"/shapes/0/radius", "1", "shapes[0].radius", "unknown key"},
    {"/shapes/0", "\"quad\"", "shapes[0]", "must be a JSON object"},
    {"/shapes/1/max", "[0.5, 0, 0.5]", "shapes[1].max", "greater than min"},
    {"/shapes/1/max", "[-0.6, 1, 0.5]", "shapes[1].max", "greater than min"},
    {"/shapes/2/radius", "-1", "shapes[2].radius", "must be a finite number > 0, got -1"},
    {"/shapes/2/radius", "0", "shapes[2].radius", "> 0"},
    {"/shapes/2/radius", "1e-50", "shapes[2].radius", "rounds to 0"},
    {"/shapes/2/center", nullptr, "shapes[2].center", "required key is missing"},
    {"/shapes/3/file", "\"meshes/missing.obj\"", "shapes[3].file", "mesh file not found"},
    {"/shapes/3/file", "\"meshes/dir.obj\"", "shapes[3].file", "is a directory"},
    {"/shapes/3/file", "\"\"", "shapes[3].file", "must be a file path"},
    {"/shapes/3/scale", "0", "shapes[3].scale", "> 0"},
    {"/shapes/3/scale", "[1, 1, 1]", "shapes[3].scale", "> 0"},
    {"/shapes/3/rotate_deg", "[0, 90]", "shapes[3].rotate_deg", "array of 3"},
    {"/shapes/3/translate", "[0, 0, 1e300]", "shapes[3].translate", "within"},
    // lights
    {"/lights/0/power", "[-1, 0, 0]", "lights[0].power", "in [0, 1e+30]"},
    {"/lights/0/power", "[1e300, 0, 0]", "lights[0].power", "in [0, 1e+30]"},
    {"/lights/0/power", nullptr, "lights[0].power", "required key is missing"},
    {"/lights/0/type", "\"area\"", "lights[0].type", "must be one of"},
    {"/lights/0/direction", "[0, 1, 0]", "lights[0].direction", "unknown key"},
    {"/lights/1/edge2", "[0, 0, 0]", "lights[1].edge2", "zero area"},
    {"/lights/1/radiance", "[1, 1, -1]", "lights[1].radiance", "in [0, 1e+30]"},
    {"/lights/1/power", "[1, 1, 1]", "lights[1].power", "unknown key"},
    {"/lights/2/direction", "[0, 0, 0]", "lights[2].direction", "non-zero"},
    {"/lights/2/direction", nullptr, "lights[2].direction", "required key is missing"},
    {"/lights/2/cone_deg", "0", "lights[2].cone_deg", "in [0.1, 180]"},
    {"/lights/2/cone_deg", "181", "lights[2].cone_deg", "in [0.1, 180]"},
    {"/lights/3/direction", "[0, 0, 0]", "lights[3].direction", "non-zero"},
    {"/lights/3/radius", "0", "lights[3].radius", "> 0"},
    {"/lights", R"([{"type": "point", "position": [0, 1, 0], "power": [0, 0, 0]}])", "lights",
     "zero power"},
    // medium
    {"/medium/sigma_a", "-1", "medium.sigma_a", ">= 0"},
    {"/medium/sigma_s", "[0.1, -0.1, 0]", "medium.sigma_s", ">= 0"},
    {"/medium/sigma_s", "\"thick\"", "medium.sigma_s", "or an array of 3"},
    {"/medium/g", "1", "medium.g", "in (-1, 1)"},
    {"/medium/g", "-1", "medium.g", "in (-1, 1)"},
    {"/medium/bounds/max", "[-1, 0, -1]", "medium.bounds.max", "greater than min"},
    {"/medium/bounds/min", nullptr, "medium.bounds.min", "required key is missing"},
    {"/medium/bounds/center", "[0, 0, 0]", "medium.bounds.center", "unknown key"},
    {"/medium/density", "1", "medium.density", "unknown key"},
    // time
    {"/time/end_ns", "0", "time.end_ns", "greater than start_ns"},
    {"/time/end_ns", "-5", "time.end_ns", "greater than start_ns"},
    {"/time", R"({"start_ns": -1.7e308, "end_ns": 1.7e308})", "time.end_ns", "out of range"},
    {"/time/frames", "0", "time.frames", "1..100000"},
    {"/time/frames", "100001", "time.frames", "1..100000"},
    {"/time/fps", "0", "time.fps", "[1, 1000]"},
    {"/time/fps", "0.0001", "time.fps", "[1, 1000]"},  // too slow for the containers
    {"/time/start_ns", "\"0\"", "time.start_ns", "finite number"},
    {"/time/duration", "1", "time.duration", "unknown key"},
    // emission
    {"/emission/mode", "\"flash\"", "emission.mode", "must be one of \"constant\", \"pulse\""},
    {"/emission/width_ns", "0", "emission.width_ns", "> 0"},
    {"/emission/width_ns", "0.7", "emission.width_ns", "whole multiple of the frame width"},
    {"/emission/width_ns", "0.25", "emission.width_ns", "whole multiple of the frame width"},
    {"/emission", R"({"mode": "constant", "width_ns": 1})", "emission.width_ns", "only"},
    {"/emission/width_ns", "1e9", "emission.width_ns", "more than"},
    // render
    {"/render/passes", "0", "render.passes", "1..10000000"},
    {"/render/passes", "10000001", "render.passes", "1..10000000"},
    {"/render/photons_per_pass", "0", "render.photons_per_pass", "1..1000000000"},
    {"/render/photons_per_pass", "1000000001", "render.photons_per_pass", "1..1000000000"},
    {"/render/max_depth", "0", "render.max_depth", "1..1000"},
    {"/render/max_depth", "1001", "render.max_depth", "1..1000"},
    {"/render/radius", "-0.1", "render.radius", ">= 0"},
    {"/render/alpha", "0", "render.alpha", "in (0, 1)"},
    {"/render/alpha", "1", "render.alpha", "in (0, 1)"},
    {"/render/camera_tof", "1", "render.camera_tof", "true or false"},
    {"/render/seed", "-1", "render.seed", "integer"},
    {"/render/seed", "1.5", "render.seed", "integer"},
    {"/render/ambient", "[-1, 0, 0]", "render.ambient", "in [0, 1e+30]"},
    {"/render/gamma", "2.2", "render.gamma", "unknown key"},
};

class SceneErrors : public test::SceneFolder {};

}  // namespace

TEST_F(SceneErrors, FullSceneIsValid) {
    EXPECT_EQ(error_of(test::full_scene().dump(), dir.string()), "no error");
}

TEST_F(SceneErrors, EachBadValueNamesFileAndKey) {
    for (const BadCase& c : kBadCases) {
        json j = test::full_scene();
        json::json_pointer p(c.pointer);
        if (c.value)
            j[p] = json::parse(c.value);
        else
            j[p.parent_pointer()].erase(p.back());
        std::string message = error_of(j.dump(2), dir.string());
        SCOPED_TRACE(std::string(c.pointer) + " = " + (c.value ? c.value : "(removed)"));
        EXPECT_EQ(message.rfind("bad.json: key '" + std::string(c.key) + "': ", 0), 0u) << message;
        EXPECT_NE(message.find(c.what), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST_F(SceneErrors, ExactMessageForTheContractExample) {
    json j = test::full_scene();
    j["shapes"][2]["radius"] = -1;
    EXPECT_EQ(error_of(j.dump(), dir.string()),
              "bad.json: key 'shapes[2].radius': must be a finite number > 0, got -1");
}

TEST_F(SceneErrors, OverridingAPulseSceneWithUnknownMaterialListsTheDefinedOnes) {
    json j = test::full_scene();
    j["shapes"][0]["material"] = "gold";
    std::string m = error_of(j.dump(), dir.string());
    EXPECT_NE(m.find("defined: glass, mirror, white"), std::string::npos) << m;
    j.erase("materials");
    j.erase("shapes");
    j["shapes"] = json::array(
        {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "gold"}}});
    m = error_of(j.dump(), dir.string());
    EXPECT_NE(m.find("no materials are defined"), std::string::npos) << m;
}

struct TextCase {
    const char* text;
    const char* prefix;  // the message must start with this
};

TEST(SceneSyntaxErrors, NameLineAndColumnOrKey) {
    const TextCase cases[] = {
        {"", "bad.json: line 1, column 1: JSON syntax error: "},
        {"{\n  \"camera\": {,\n}", "bad.json: line 2, column 14: JSON syntax error: "},
        {"{\"a\": 1,}", "bad.json: line 1, column 9: JSON syntax error: "},
        {"{\"a\": \"x\ny\"}", "bad.json: line 1, column 9: JSON syntax error: "},
        {"{\"a\": NaN}", "bad.json: line 1, column 7: JSON syntax error: "},
        {"{\n \"camera\": {\"width\": 1e999}}",
         "bad.json: line 2, column 22: number out of range: 1e999"},
        {"[1, 2]", "bad.json: top level: must be a JSON object"},
        {"{\"camera\": {\"width\": 1, \"width\": 2}}",
         "bad.json: key 'camera.width': duplicate key"},
        {"{\"shapes\": [{}, {\"type\": \"quad\", \"type\": \"box\"}]}",
         "bad.json: key 'shapes[1].type': duplicate key"},
        {"{\"a\": [[1], {\"b\": [{}, {\"c\": 1, \"c\": 2}]}]}",
         "bad.json: key 'a[1].b[1].c': duplicate key"},
        {"{\"lights\": 1, \"lights\": 2}", "bad.json: key 'lights': duplicate key"},
        {"{\"caméra\\n\": 1}", "bad.json: key 'caméra\\x0a': unknown key"},
    };
    for (const TextCase& c : cases) {
        std::string message = error_of(c.text, "");
        EXPECT_EQ(message.rfind(c.prefix, 0), 0u) << "text: " << c.text << "\nmessage: " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST(SceneSyntaxErrors, DeepNestingIsRejectedNotACrash) {
    const int depth = 200000;
    std::string arrays = std::string(depth, '[') + std::string(depth, ']');
    EXPECT_EQ(error_of(arrays, "").rfind("bad.json: key '[0][0]", 0), 0u);
    std::string objects;
    for (int i = 0; i < depth; ++i) objects += "{\"camera\":";
    objects += "1" + std::string(depth, '}');
    EXPECT_NE(error_of(objects, "").find("nested more than 64 levels"), std::string::npos);
}

// A slip of the keyboard is answered with the nearest valid name, for keys and for values.
TEST(SceneSyntaxErrors, MisspeltKeysAndValuesSuggestTheNearest) {
    const std::string base = R"({"camera": {"position": [0, 1, 3], "look_at": [0, 1, 0]}, "lights": [)";
    auto message = [&](const std::string& light) {
        try {
            sl::parse_scene_text(base + light + "]}", "s.json", "");
        } catch (const sl::InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    std::string m = message(R"({"type": "quad", "corner": [0, 2, 0], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "Radiance": [1, 1, 1]})");
    EXPECT_NE(m.find("key 'lights[0].Radiance': unknown key: did you mean 'radiance'?"), std::string::npos) << m;
    m = message(R"({"type": "Spot", "position": [0, 2, 0], "power": [1, 1, 1]})");
    EXPECT_NE(m.find("(did you mean \"spot\"?)"), std::string::npos) << m;
    m = message(R"({"type": "point", "positoin": [0, 2, 0], "power": [1, 1, 1]})");
    EXPECT_NE(m.find("did you mean 'position'?"), std::string::npos) << m;
    // Nothing close: no guess.
    m = message(R"({"type": "point", "position": [0, 2, 0], "power": [1, 1, 1], "colour": [1, 1, 1]})");
    EXPECT_EQ(m.find("did you mean"), std::string::npos) << m;
}
