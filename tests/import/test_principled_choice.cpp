// The choice of how metallic-roughness draws its diffuse base (docs/materials.md, "The diffuse
// base"): a gltf shape's "principled", --gltf-principled for the gltf shapes that do not say
// (and for a model rendered directly), and a metallic_roughness material's own "principled",
// each followed through the command line's own loading (load_scene) to the BSDF the renderer
// builds (MaterialTable). Anything else is refused, naming the key or the flag.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "config/command_line.h"
#include "config/parse_scene.h"
#include "core/import/mesh_data.h"
#include "core/import/mesh_instances.h"
#include "core/material_table.h"
#include "foundation/errors.h"
#include "pipeline/render_command.h"
#include "tests/common/temp_dir.h"
#include "tests/import/model_writers.h"

namespace sl::test {
namespace {

// A red plastic quad under Blender's default layer (specular 1 = F0 4 %, roughness 0.2) and, so
// that the file alone is lit, an emissive quad above it.
void write_plastic_model(const std::string& path, const std::string& generator = "") {
    ModelMesh m;
    m.quad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0);
    m.quad({-0.2f, 2, -0.2f}, {0, 0, 0.4f}, {0.4f, 0, 0}, 1);
    ModelMaterial plastic("plastic", Vec3(0.8f, 0.1f, 0.1f));
    plastic.specular = 1;
    plastic.roughness = 0.2f;
    write_gltf(path, m, {plastic, {"lamp", Vec3(0), Vec3(5)}}, true, nullptr, generator);
}

SceneDesc load(const std::vector<std::string>& args) {
    std::vector<const char*> argv{"slowlight", "info"};
    for (const std::string& a : args) argv.push_back(a.c_str());
    return load_scene(parse_command_line(static_cast<int>(argv.size()), argv.data()));
}

// The material index of a shape's first triangle (a file placed once is baked into `mesh`; one
// that several entries place the same way is held once and instanced).
int material_of(const ShapeDesc& s) {
    if (s.mesh && !s.mesh->tri_material.empty()) return s.mesh->tri_material[0];
    if (s.instances && !s.instances->meshes.empty()) return s.instances->meshes[0].mesh->tri_material[0];
    return s.material;
}

// Per shape: whether the renderer's BSDF on it draws the blender3 base.
std::vector<bool> blender3_per_shape(const SceneDesc& scene) {
    const MaterialTable table(scene);
    std::vector<bool> out;
    for (const ShapeDesc& s : scene.shapes) {
        const SurfaceMaterial& m = table[material_of(s)];
        EXPECT_EQ(m.type, MaterialType::MetallicRoughness);
        EXPECT_EQ(m.bsdf.blender3_base, scene.materials[static_cast<size_t>(material_of(s))].principled ==
                                            PrincipledBase::Blender3);
        out.push_back(m.bsdf.blender3_base);
    }
    return out;
}

TEST(PrincipledChoice, SceneKeysAndTheFlagReachTheRenderersBsdf) {
    TempDir dir;
    write_plastic_model(dir.file("plastic.glb"));
    std::ofstream(dir.file("scene.json")) << R"({
      "camera": {"position": [0, 3, 3], "look_at": [0, 0, 0]},
      "materials": {
        "mine": {"type": "metallic_roughness", "base_color": [0.8, 0.1, 0.1], "principled": "blender3"},
        "plain": {"type": "metallic_roughness", "base_color": [0.8, 0.1, 0.1]}},
      "shapes": [
        {"type": "gltf", "file": "plastic.glb"},
        {"type": "gltf", "file": "plastic.glb", "principled": "blender3", "translate": [3, 0, 0]},
        {"type": "gltf", "file": "plastic.glb", "principled": "energy_conserving", "translate": [-3, 0, 0]},
        {"type": "quad", "corner": [-1, -1, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2], "material": "mine"},
        {"type": "quad", "corner": [-1, -2, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2], "material": "plain"}],
      "lights": [{"type": "point", "position": [0, 2, 0], "power": [10, 10, 10]}]})";
    // The shapes' own keys; the others energy-conserving.
    EXPECT_EQ(blender3_per_shape(load({dir.file("scene.json")})),
              (std::vector<bool>{false, true, false, true, false}));
    // The flag is the default of the gltf shape that does not say; the keys win; a scene's own
    // material is its own.
    EXPECT_EQ(blender3_per_shape(load({dir.file("scene.json"), "--gltf-principled", "blender3"})),
              (std::vector<bool>{true, true, false, true, false}));
    EXPECT_EQ(blender3_per_shape(load({dir.file("scene.json"), "--gltf-principled", "energy_conserving"})),
              (std::vector<bool>{false, true, false, true, false}));
}

TEST(PrincipledChoice, AModelRenderedDirectlyTakesTheFlag) {
    TempDir dir;
    write_plastic_model(dir.file("plastic.glb"));
    auto plastic_bsdf = [&](const std::vector<std::string>& args) {
        const SceneDesc scene = load(args);
        const MaterialTable table(scene);
        for (size_t i = 0; i < table.size(); ++i)
            if (scene.materials[i].name == "plastic") return table[static_cast<int>(i)].bsdf;
        ADD_FAILURE() << "no plastic material";
        return bsdf::Bsdf{};
    };
    EXPECT_FALSE(plastic_bsdf({dir.file("plastic.glb")}).blender3_base);
    const bsdf::Bsdf b = plastic_bsdf({dir.file("plastic.glb"), "--gltf-principled", "blender3"});
    EXPECT_TRUE(b.blender3_base);
    EXPECT_EQ(b.kind, bsdf::Kind::MetallicRoughness);
    EXPECT_NEAR(b.base.x, 0.8f, 1e-6f);  // the rest of the material as read
}

// A file Blender 3.x's exporter wrote was made from Principled v1 materials: unless told
// otherwise it is drawn as Cycles 3.x draws them; Blender 4.x's (Principled v2) and any other
// writer's get the energy-conserving default.
TEST(PrincipledChoice, AFileBlender3WroteIsDrawnAsBlender3UnlessToldOtherwise) {
    TempDir dir;
    write_plastic_model(dir.file("b34.glb"), "Khronos glTF Blender I/O v3.4.50");
    write_plastic_model(dir.file("b29.glb"), "Khronos glTF Blender I/O v1.6.16");
    write_plastic_model(dir.file("b40.glb"), "Khronos glTF Blender I/O v4.0.44");
    write_plastic_model(dir.file("other.glb"), "Blender I/O v3.4.50 (a look-alike)");
    auto blender3 = [&](const std::vector<std::string>& args) {
        const SceneDesc scene = load(args);
        const MaterialTable table(scene);
        for (size_t i = 0; i < table.size(); ++i)
            if (scene.materials[i].name == "plastic") return table[static_cast<int>(i)].bsdf.blender3_base;
        ADD_FAILURE() << "no plastic material";
        return false;
    };
    EXPECT_TRUE(blender3({dir.file("b34.glb")}));
    EXPECT_TRUE(blender3({dir.file("b29.glb")}));
    EXPECT_FALSE(blender3({dir.file("b40.glb")}));
    EXPECT_FALSE(blender3({dir.file("other.glb")}));
    EXPECT_FALSE(blender3({dir.file("b34.glb"), "--gltf-principled", "energy_conserving"}));
    EXPECT_TRUE(blender3({dir.file("b40.glb"), "--gltf-principled", "blender3"}));
    // In a scene: the entry's key, then the flag, then the writer.
    std::ofstream(dir.file("scene.json")) << R"({
      "camera": {"position": [0, 3, 3], "look_at": [0, 0, 0]},
      "shapes": [
        {"type": "gltf", "file": "b34.glb"},
        {"type": "gltf", "file": "b34.glb", "principled": "energy_conserving", "translate": [3, 0, 0]},
        {"type": "gltf", "file": "b40.glb", "translate": [-3, 0, 0]}],
      "lights": [{"type": "point", "position": [0, 2, 0], "power": [10, 10, 10]}]})";
    EXPECT_EQ(blender3_per_shape(load({dir.file("scene.json")})), (std::vector<bool>{true, false, false}));
    EXPECT_EQ(blender3_per_shape(load({dir.file("scene.json"), "--gltf-principled", "energy_conserving"})),
              (std::vector<bool>{false, false, false}));
}

void expect_refused(const std::string& scene_text, const std::string& fragment) {
    try {
        parse_scene_text(scene_text, "scene.json", ".");
        ADD_FAILURE() << "accepted: " << scene_text;
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
}

TEST(PrincipledChoice, BadValuesAreRefusedNamingTheKeyOrFlag) {
    TempDir dir;
    write_plastic_model(dir.file("plastic.glb"));
    const std::string head = R"({"camera": {"position": [0, 3, 3], "look_at": [0, 0, 0]},
        "lights": [{"type": "point", "position": [0, 2, 0], "power": [10, 10, 10]}], )";
    const std::string file = "\"" + dir.file("plastic.glb") + "\"";
    expect_refused(head + R"("shapes": [{"type": "gltf", "file": )" + file + R"(, "principled": "blender4"}]})",
                   "key 'shapes[0].principled'");
    expect_refused(head + R"("materials": {"p": {"type": "metallic_roughness", "principled": "cycles"}},
                   "shapes": []})",
                   "key 'materials.p.principled'");
    // Only metallic_roughness has a diffuse base to choose for.
    expect_refused(head + R"("materials": {"d": {"type": "diffuse", "principled": "blender3"}}, "shapes": []})",
                   "unknown key");
    // An entry that names a scene material does not draw the file's materials.
    expect_refused(head + R"("materials": {"w": {"type": "diffuse"}}, "shapes": [{"type": "gltf", "file": )" + file +
                       R"(, "material": "w", "principled": "blender3"}]})",
                   "applies to the file's own materials");
    const char* argv[] = {"slowlight", "info", "scene.json", "--gltf-principled", "blender4"};
    try {
        parse_command_line(5, argv);
        ADD_FAILURE() << "accepted --gltf-principled blender4";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "command line: --gltf-principled: must be energy_conserving or blender3, got 'blender4'");
    }
}

}  // namespace
}  // namespace sl::test
