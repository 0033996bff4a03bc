// glTF metallic-roughness and MTL materials as slowlight's materials (and how camera paths use
// their BSDFs, core/material_table.h), and the texture wrap modes.
#include <gtest/gtest.h>

#include <fstream>

#include "foundation/errors.h"
#include "core/import/imported_file.h"
#include "core/material_table.h"
#include "core/texture.h"
#include "tests/common/temp_dir.h"
#include "tests/import/model_writers.h"
#include "tests/pipeline/run_program.h"

namespace sl::test {
namespace {

TEST(MaterialMapping, GltfMetallicRoughnessTransmissionEmission) {
    TempDir dir;
    ModelMesh m;
    for (int i = 0; i < 5; ++i) m.quad({static_cast<float>(i), 0, 0}, {1, 0, 0}, {0, 1, 0}, i);
    std::vector<ModelMaterial> mats = {{"matte", {0.2f, 0.4f, 0.6f}}, {"chrome", Vec3(0.9f)}, {"brushed", Vec3(0.5f)},
                                       {"glass", Vec3(1)}, {"lamp", Vec3(0), {2, 4, 8}}};
    write_gltf(dir.file("m.gltf"), m, mats, false);
    std::ifstream in(dir.file("m.gltf"));
    auto j = nlohmann::json::parse(in);
    j["materials"][1]["pbrMetallicRoughness"]["metallicFactor"] = 1.0;
    j["materials"][1]["pbrMetallicRoughness"]["roughnessFactor"] = 0.0;
    j["materials"][2]["pbrMetallicRoughness"]["metallicFactor"] = 1.0;
    j["materials"][2]["pbrMetallicRoughness"]["roughnessFactor"] = 0.5;
    j["materials"][3]["extensions"] = {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                                       {"KHR_materials_ior", {{"ior", 1.33}}}};
    j["materials"][4]["doubleSided"] = true;
    j["extensionsUsed"] = {"KHR_materials_emissive_strength", "KHR_materials_transmission", "KHR_materials_ior"};
    std::ofstream(dir.file("m.gltf")) << j.dump();
    ImportedFile f = read_gltf(dir.file("m.gltf"), true);
    ASSERT_EQ(f.materials.size(), 5u);
    for (const MaterialDesc& m : f.materials) EXPECT_EQ(m.type, MaterialType::MetallicRoughness);
    // Evaluated as GGX: the matte base gathers, the smooth metal is followed, the rough metal
    // (roughness 0.5) gathers, the glass is followed.
    EXPECT_EQ(glossy_use(f.materials[0]), GlossyUse::Gather);
    EXPECT_FLOAT_EQ(f.materials[0].albedo.y, 0.4f);
    EXPECT_EQ(glossy_use(f.materials[1]), GlossyUse::Follow);
    EXPECT_FLOAT_EQ(f.materials[1].albedo.x, 0.9f);
    EXPECT_FLOAT_EQ(f.materials[1].metallic, 1.0f);
    EXPECT_FLOAT_EQ(f.materials[1].roughness, 0.0f);
    EXPECT_EQ(glossy_use(f.materials[2]), GlossyUse::Gather);
    EXPECT_FLOAT_EQ(f.materials[2].roughness, 0.5f);
    EXPECT_EQ(glossy_use(f.materials[3]), GlossyUse::Follow);
    EXPECT_FLOAT_EQ(f.materials[3].ior, 1.33f);
    EXPECT_FLOAT_EQ(f.materials[3].transmission, 1.0f);
    EXPECT_TRUE(f.materials[4].emits());
    EXPECT_TRUE(f.materials[4].double_sided);
    EXPECT_FLOAT_EQ(f.materials[4].emission.z, 8.0f);  // factor (0.25, 0.5, 1) x strength 8
    EXPECT_FLOAT_EQ(f.materials[4].emission.x, 2.0f);
    for (const std::string& w : f.warnings) EXPECT_EQ(w.find("material 'brushed'"), std::string::npos) << w;
    EXPECT_EQ(f.mesh.triangle_count(), 10u);
    EXPECT_EQ(f.mesh.normals.size(), f.mesh.positions.size());
    EXPECT_EQ(f.mesh.uvs.size(), 2 * f.mesh.positions.size());
}

TEST(MaterialMapping, MtlIllumKdKeNi) {
    TempDir dir;
    std::ofstream(dir.file("m.mtl")) << "newmtl mirror\nKs 0.9 0.8 0.7\nillum 3\n"
                                     << "newmtl glass\nNi 1.7\nillum 7\n"
                                     << "newmtl lamp\nKd 0.1 0.2 0.3\nKe 5 6 7\n";
    std::ofstream(dir.file("m.obj")) << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\n"
                                     << "usemtl mirror\nf 1 2 3\nusemtl glass\nf 1 2 3\nusemtl lamp\nf 1 2 3\n";
    ImportedFile f = read_obj_mtl(dir.file("m.obj"), true);
    ASSERT_EQ(f.materials.size(), 3u);
    EXPECT_EQ(f.materials[0].type, MaterialType::Mirror);  // no Ns: perfectly smooth, as before
    EXPECT_FLOAT_EQ(f.materials[0].reflectance.y, 0.8f);
    EXPECT_EQ(f.materials[1].type, MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(f.materials[1].ior, 1.7f);
    EXPECT_EQ(f.materials[2].type, MaterialType::Diffuse);
    EXPECT_FLOAT_EQ(f.materials[2].albedo.z, 0.3f);
    EXPECT_FLOAT_EQ(f.materials[2].emission.y, 6.0f);
    EXPECT_EQ(f.mesh.tri_material, (std::vector<int32_t>{0, 1, 2}));
    EXPECT_TRUE(f.mesh.normals.empty());  // no vn: flat
}

// A cube as Blender 3.4 exports it, its materials in two libraries: named on two `mtllib`
// lines, or both on one line. (Two lines crashed: the second library's materials were looked
// up in the first's lists.)
void write_blender_cube(const TempDir& dir, const std::string& mtllib_lines) {
    auto mtl = [](const std::string& name, const char* kd, const char* ke) {
        return "newmtl " + name + "\nNs 250.000000\nKa 1.000000 1.000000 1.000000\nKd " + kd +
               "\nKs 0.500000 0.500000 0.500000\nKe " + ke + "\nNi 1.450000\nd 1.000000\nillum 2\n";
    };
    std::ofstream(dir.file("cube.mtl")) << "# Blender 3.4.1 MTL File: 'None'\n# www.blender.org\n\n"
                                        << mtl("Material", "0.800000 0.800000 0.800000", "0.000000 0.000000 0.000000");
    std::ofstream(dir.file("lamp.mtl")) << "# Blender 3.4.1 MTL File: 'None'\n# www.blender.org\n\n"
                                        << mtl("Lamp", "0.000000 0.000000 0.000000", "5.000000 5.000000 5.000000");
    std::ofstream o(dir.file("cube.obj"));
    o << "# Blender 3.4.1\n# www.blender.org\n" << mtllib_lines << "o Cube\n";
    for (const char* v : {"1.000000 1.000000 -1.000000", "1.000000 -1.000000 -1.000000", "1.000000 1.000000 1.000000",
                          "1.000000 -1.000000 1.000000", "-1.000000 1.000000 -1.000000", "-1.000000 -1.000000 -1.000000",
                          "-1.000000 1.000000 1.000000", "-1.000000 -1.000000 1.000000"})
        o << "v " << v << "\n";
    o << "vt 0.625000 0.500000\nvt 0.875000 0.500000\nvt 0.875000 0.750000\nvt 0.625000 0.750000\n"
      << "vn -0.0000 1.0000 -0.0000\nvn -0.0000 -1.0000 -0.0000\ns 0\n"
      << "usemtl Material\nf 1/1/1 5/2/1 7/3/1 3/4/1\n"
      << "usemtl Lamp\nf 2/1/2 4/2/2 8/3/2 6/4/2\n";
}

TEST(MaterialMapping, MtlFromSeveralLibrariesAsBlenderWritesThem) {
    for (const std::string lines : {"mtllib cube.mtl\nmtllib lamp.mtl\n", "mtllib cube.mtl lamp.mtl\n",
                                    "mtllib cube.mtl\nmtllib lamp.mtl\nmtllib cube.mtl\n"}) {
        SCOPED_TRACE(lines);
        TempDir dir;
        write_blender_cube(dir, lines);
        ImportedFile f = read_obj_mtl(dir.file("cube.obj"), true);
        ASSERT_EQ(f.materials.size(), 2u);  // a library named twice is read once
        EXPECT_EQ(f.materials[0].name, "Material");
        EXPECT_FLOAT_EQ(f.materials[0].albedo.x, 0.8f);
        EXPECT_FALSE(f.materials[0].emits());
        EXPECT_EQ(f.materials[1].name, "Lamp");
        EXPECT_FLOAT_EQ(f.materials[1].emission.y, 5.0f);
        EXPECT_EQ(f.mesh.tri_material, (std::vector<int32_t>{0, 0, 1, 1}));
        // The program renders it (the lamp lights the scene).
        ProgramResult r = run_program({"render", dir.file("cube.obj"), "--width", "16", "--height", "16", "--passes",
                                       "1", "--photons", "1000", "--frames", "2", "--no-progress", "--stats",
                                       dir.file("s.json")});
        EXPECT_EQ(r.exit_code, 0) << r.err;
        EXPECT_TRUE(r.error_lines().empty()) << r.err;
    }
}

// Blender 3.4's glTF exporter at default settings: the default Principled BSDF (base 0.8,
// metallic 0, roughness 0.5, with KHR_materials_specular and _ior), and an Emission-only
// material (a black base colour, metallic and roughness left at glTF's default 1). Neither is
// approximated in a way a viewer sees, so neither warns.
TEST(MaterialMapping, BlenderDefaultPrincipledAndEmissionOnlyGiveNoWarning) {
    TempDir dir;
    ModelMesh m;
    for (int i = 0; i < 3; ++i) m.quad({static_cast<float>(i), 0, 0}, {1, 0, 0}, {0, 1, 0}, i);
    write_gltf(dir.file("b.gltf"), m, {{"Material", Vec3(0.8f)}, {"Lamp", Vec3(0), {5, 5, 5}}, {"Metal", Vec3(0.9f)}}, false);
    std::ifstream in(dir.file("b.gltf"));
    auto j = nlohmann::json::parse(in);
    j["materials"][0]["pbrMetallicRoughness"] = {{"baseColorFactor", {0.8, 0.8, 0.8, 1}}, {"metallicFactor", 0},
                                                 {"roughnessFactor", 0.5}};
    j["materials"][0]["extensions"] = {{"KHR_materials_specular", {{"specularColorFactor", {1.186, 1.186, 1.186}}}},
                                       {"KHR_materials_ior", {{"ior", 1.45}}}};
    j["materials"][1]["pbrMetallicRoughness"] = {{"baseColorFactor", {0, 0, 0, 1}}};  // metallic, roughness: 1
    j["materials"][2]["pbrMetallicRoughness"] = {{"baseColorFactor", {0.9, 0.9, 0.9, 1}}, {"metallicFactor", 1},
                                                 {"roughnessFactor", 0.3}};
    j["materials"][2]["extensions"] = {{"KHR_materials_specular", {{"specularFactor", 0.5}}}};
    j["extensionsUsed"] = {"KHR_materials_emissive_strength", "KHR_materials_specular", "KHR_materials_ior"};
    std::ofstream(dir.file("b.gltf")) << j.dump();
    ImportedFile f = read_gltf(dir.file("b.gltf"), true);
    ASSERT_EQ(f.materials.size(), 3u);
    EXPECT_FLOAT_EQ(f.materials[0].ior, 1.45f);
    EXPECT_FLOAT_EQ(f.materials[0].specular_color.x, 1.186f);
    EXPECT_FLOAT_EQ(f.materials[0].roughness, 0.5f);
    EXPECT_EQ(glossy_use(f.materials[0]), GlossyUse::Gather);
    EXPECT_TRUE(f.materials[1].emits());
    EXPECT_FLOAT_EQ(f.materials[1].metallic, 1.0f);
    EXPECT_FLOAT_EQ(f.materials[2].specular, 0.5f);
    // Nothing is approximated: no warning, none about the extensions.
    EXPECT_TRUE(f.warnings.empty()) << f.warnings[0];
}

// MTL's Ns as Blender pairs it with roughness (Ns = 1000 (1 - r)^2), and Ks as a specular layer.
TEST(MaterialMapping, MtlNsAndKsAsGgxMaterials) {
    TempDir dir;
    std::ofstream(dir.file("m.mtl")) << "newmtl plastic\nNs 250\nKd 0.8 0.1 0.1\nKs 0.5 0.5 0.5\nillum 2\n"
                                     << "newmtl metal\nNs 490\nKs 0.9 0.8 0.7\nillum 3\n"
                                     << "newmtl frosted\nNs 0\nNi 1.45\nillum 4\n"
                                     << "newmtl polished\nNs 1000\nKs 1 1 1\nillum 3\n";
    std::ofstream(dir.file("m.obj")) << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl plastic\nf 1 2 3\n"
                                     << "usemtl metal\nf 1 2 3\nusemtl frosted\nf 1 2 3\nusemtl polished\nf 1 2 3\n";
    ImportedFile f = read_obj_mtl(dir.file("m.obj"), true);
    ASSERT_EQ(f.materials.size(), 4u);
    EXPECT_EQ(f.materials[0].type, MaterialType::MetallicRoughness);
    EXPECT_NEAR(f.materials[0].roughness, 0.5f, 1e-6f);  // Blender's default roughness
    EXPECT_FLOAT_EQ(f.materials[0].specular, 1.0f);       // Ks 0.5: glass's 4 %
    EXPECT_FLOAT_EQ(f.materials[0].albedo.x, 0.8f);
    EXPECT_EQ(f.materials[1].type, MaterialType::Conductor);
    EXPECT_NEAR(f.materials[1].roughness, 0.3f, 1e-6f);
    EXPECT_FLOAT_EQ(f.materials[1].reflectance.y, 0.8f);
    EXPECT_EQ(f.materials[2].type, MaterialType::RoughDielectric);
    EXPECT_FLOAT_EQ(f.materials[2].roughness, 1.0f);
    EXPECT_FLOAT_EQ(f.materials[2].ior, 1.45f);
    EXPECT_EQ(f.materials[3].type, MaterialType::Conductor);
    EXPECT_FLOAT_EQ(f.materials[3].roughness, 0.0f);
    EXPECT_EQ(glossy_use(f.materials[3]), GlossyUse::Follow);
    // Their BSDFs are evaluated: no material is warned about.
    std::string all;
    for (const std::string& w : f.warnings) all += w + "\n";
    for (const char* name : {"'plastic'", "'metal'", "'frosted'", "'polished'"})
        EXPECT_EQ(all.find(name), std::string::npos) << all;
}

// A scene file's own GGX materials render with their BSDFs, and nothing is warned about.
TEST(MaterialMapping, SceneFileGgxMaterialsRenderWithoutWarnings) {
    TempDir dir;
    std::ofstream(dir.file("s.json")) << R"({"camera": {"position": [0, 1, 3], "look_at": [0, 1, 0], "width": 8, "height": 8},
      "materials": {"brushed": {"type": "conductor", "reflectance": [0.9, 0.6, 0.5], "roughness": 0.3},
                    "polished": {"type": "conductor", "eta": [0.2, 0.9, 1.1], "k": [3.9, 2.4, 2.1], "roughness": 0.05},
                    "plastic": {"type": "metallic_roughness", "base_color": [0.8, 0.1, 0.1]},
                    "unused": {"type": "rough_dielectric", "roughness": 0.5}},
      "shapes": [{"type": "quad", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2], "material": "brushed"},
                 {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.3, "material": "plastic"},
                 {"type": "sphere", "center": [0.6, 0.5, 0], "radius": 0.2, "material": "polished"}],
      "lights": [{"type": "point", "position": [0, 1.5, 0], "power": [10, 10, 10]}],
      "time": {"frames": 2}, "render": {"passes": 1, "photons_per_pass": 1000}})";
    ProgramResult r = run_program({"render", dir.file("s.json"), "--no-progress", "-o", dir.file("out.mp4")});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    size_t warnings = 0;
    for (size_t at = r.err.find("warning:"); at != std::string::npos; at = r.err.find("warning:", at + 1)) ++warnings;
    EXPECT_EQ(warnings, 0u) << r.err;
}

TEST(MaterialMapping, WrapModesAndBilinear) {
    TextureImage t;
    t.width = 4;
    t.height = 1;
    t.format = TexelFormat::Half;  // 0..3 are exact halves
    for (float v : {0.0f, 1.0f, 2.0f, 3.0f}) t.halves.insert(t.halves.end(), 3, float_to_half(v));
    // Texel centres are at u = (i + 0.5) / 4; halfway between texels 1 and 2 is their mean.
    EXPECT_FLOAT_EQ(t.sample(0.5f, 0.5f).x, 1.5f);
    EXPECT_FLOAT_EQ(t.sample(0.375f, 0.5f).x, 1.0f);
    // Past the right edge: repeat blends texel 3 with texel 0, clamp stays on 3, mirrored on 3.
    const float u = 1.0f;  // halfway between texel 3's centre and the next one
    t.wrap_s = TextureWrap::Repeat;
    EXPECT_FLOAT_EQ(t.sample(u, 0.5f).x, 1.5f);
    t.wrap_s = TextureWrap::Clamp;
    EXPECT_FLOAT_EQ(t.sample(u, 0.5f).x, 3.0f);
    t.wrap_s = TextureWrap::MirroredRepeat;
    EXPECT_FLOAT_EQ(t.sample(u, 0.5f).x, 3.0f);
    EXPECT_FLOAT_EQ(t.sample(1.375f, 0.5f).x, 2.0f);  // mirrored: texel 5 is texel 2
    t.wrap_s = TextureWrap::Repeat;
    EXPECT_FLOAT_EQ(t.sample(1.375f, 0.5f).x, 1.0f);  // repeated: texel 5 is texel 1
    EXPECT_FLOAT_EQ(t.sample(-0.625f, 0.5f).x, 1.0f);
}

}  // namespace
}  // namespace sl::test
