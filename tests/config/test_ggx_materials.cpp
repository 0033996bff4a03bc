// The GGX material types of the scene file (conductor, rough_dielectric, metallic_roughness):
// their values and defaults as parsed, and one error line for each value out of range.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "config/parse_scene.h"
#include "foundation/errors.h"

namespace sl {
namespace {

using nlohmann::json;

json scene_with(const json& materials) {
    json j = json::parse(R"({
      "camera": {"position": [0, 1, 3], "look_at": [0, 1, 0]},
      "lights": [{"type": "point", "position": [0, 1, 0], "power": [1, 1, 1]}],
      "shapes": [{"type": "quad", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2], "material": "m"}]
    })");
    j["materials"] = materials;
    return j;
}

MaterialDesc parse_one(const json& m) {
    SceneDesc s = parse_scene_text(scene_with({{"m", m}}).dump(), "ggx.json", ".");
    return s.materials.at(0);
}

std::string error_of(const json& m) {
    try {
        parse_one(m);
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

TEST(GgxMaterials, ConductorFromReflectanceOrComplexIndex) {
    MaterialDesc a = parse_one(json::parse(R"({"type": "conductor", "reflectance": [0.9, 0.6, 0.5], "roughness": 0.3})"));
    EXPECT_EQ(a.type, MaterialType::Conductor);
    EXPECT_FLOAT_EQ(a.reflectance.y, 0.6f);
    EXPECT_FLOAT_EQ(a.roughness, 0.3f);
    EXPECT_FALSE(a.complex_ior);
    MaterialDesc b = parse_one(json::parse(R"({"type": "conductor", "eta": [0.18, 0.42, 1.37], "k": [3.42, 2.35, 1.77]})"));
    EXPECT_TRUE(b.complex_ior);
    EXPECT_FLOAT_EQ(b.eta.z, 1.37f);
    EXPECT_FLOAT_EQ(b.k.x, 3.42f);
    EXPECT_FLOAT_EQ(b.roughness, 0.5f);  // the default, as Blender's
}

TEST(GgxMaterials, RoughDielectricAndMetallicRoughness) {
    MaterialDesc g = parse_one(json::parse(R"({"type": "rough_dielectric", "ior": 1.33, "roughness": 0.2})"));
    EXPECT_EQ(g.type, MaterialType::RoughDielectric);
    EXPECT_FLOAT_EQ(g.ior, 1.33f);
    EXPECT_FLOAT_EQ(g.roughness, 0.2f);
    MaterialDesc p = parse_one(json::parse(R"({"type": "metallic_roughness", "base_color": [0.8, 0.1, 0.1],
        "metallic": 0.25, "roughness": 0.2, "ior": 1.45, "specular": 0.5, "transmission": 0.1})"));
    EXPECT_EQ(p.type, MaterialType::MetallicRoughness);
    EXPECT_FLOAT_EQ(p.albedo.x, 0.8f);
    EXPECT_FLOAT_EQ(p.metallic, 0.25f);
    EXPECT_FLOAT_EQ(p.roughness, 0.2f);
    EXPECT_FLOAT_EQ(p.ior, 1.45f);
    EXPECT_FLOAT_EQ(p.specular, 0.5f);
    EXPECT_FLOAT_EQ(p.transmission, 0.1f);
    MaterialDesc d = parse_one(json::parse(R"({"type": "metallic_roughness"})"));
    EXPECT_FLOAT_EQ(d.metallic, 0);
    EXPECT_FLOAT_EQ(d.roughness, 0.5f);
    EXPECT_FLOAT_EQ(d.specular, 1);
    EXPECT_FLOAT_EQ(d.albedo.y, 0.8f);
}

TEST(GgxMaterials, OutOfRangeValuesGiveOneErrorNamingTheKey) {
    struct Bad { const char* material; const char* key; const char* what; };
    const Bad cases[] = {
        {R"({"type": "conductor", "roughness": 1.5})", "materials.m.roughness", "[0, 1]"},
        {R"({"type": "conductor", "roughness": -0.1})", "materials.m.roughness", "[0, 1]"},
        {R"({"type": "conductor", "reflectance": [1, 1, 1.2]})", "materials.m.reflectance", "[0, 1]"},
        {R"({"type": "conductor", "reflectance": [1, 1, 1], "eta": [1, 1, 1], "k": [1, 1, 1]})",
         "materials.m.reflectance", "not both"},
        {R"({"type": "conductor", "eta": [1, 1, 1]})", "materials.m.eta", "needs both"},
        {R"({"type": "conductor", "k": [1, 1, 1]})", "materials.m.k", "needs both"},
        {R"({"type": "conductor", "eta": [0, 1, 1], "k": [1, 1, 1]})", "materials.m.eta", "(0, 100)"},
        {R"({"type": "conductor", "eta": [1, 1, 1], "k": [-1, 1, 1]})", "materials.m.k", "[0, 100]"},
        {R"({"type": "conductor", "ior": 1.5})", "materials.m.ior", "unknown key"},
        {R"({"type": "rough_dielectric", "ior": 1})", "materials.m.ior", "differ from 1"},
        {R"({"type": "rough_dielectric", "ior": 0})", "materials.m.ior", "(0, 100)"},
        {R"({"type": "rough_dielectric", "roughness": 2})", "materials.m.roughness", "[0, 1]"},
        {R"({"type": "metallic_roughness", "metallic": 1.1})", "materials.m.metallic", "[0, 1]"},
        {R"({"type": "metallic_roughness", "specular": -1})", "materials.m.specular", "[0, 1]"},
        {R"({"type": "metallic_roughness", "transmission": 2})", "materials.m.transmission", "[0, 1]"},
        {R"({"type": "metallic_roughness", "base_color": [2, 0, 0]})", "materials.m.base_color", "[0, 1]"},
        {R"({"type": "metallic_roughness", "transmission": 1, "ior": 1})", "materials.m.ior", "differ from 1"},
        {R"({"type": "metallic_roughness", "albedo": [1, 1, 1]})", "materials.m.albedo", "unknown key"},
    };
    for (const Bad& c : cases) {
        const std::string e = error_of(json::parse(c.material));
        EXPECT_NE(e.find("ggx.json"), std::string::npos) << c.material << ": " << e;
        EXPECT_NE(e.find(c.key), std::string::npos) << c.material << ": " << e;
        EXPECT_NE(e.find(c.what), std::string::npos) << c.material << ": " << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << "one line: " << e;
    }
}

}  // namespace
}  // namespace sl
