// Bad model files: one `error:` line naming the file and what is wrong, exit status 2.
#include <gtest/gtest.h>

#include <fstream>

#include "tests/common/temp_dir.h"
#include "tests/import/model_writers.h"
#include "tests/pipeline/run_program.h"

namespace sl::test {
namespace {

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// Runs `slowlight info FILE` and expects one error line naming `name` and saying `what`.
void expect_rejected(const std::string& file, const std::string& name, const std::string& what) {
    ProgramResult r = run_program({"info", file});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    auto lines = r.error_lines();
    ASSERT_EQ(lines.size(), 1u) << r.err;
    EXPECT_NE(lines[0].find(name), std::string::npos) << lines[0];
    EXPECT_NE(lines[0].find(what), std::string::npos) << lines[0];
}

const char* kQuadObj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

// An OBJ that is lit: its material emits.
std::string lit_obj(const TempDir& dir, const std::string& body, const std::string& mtl_extra = "") {
    write_text(dir.file("lit.mtl"), "newmtl lamp\nKd 0 0 0\nKe 1 1 1\n" + mtl_extra);
    return "mtllib lit.mtl\nusemtl lamp\n" + body;
}

TEST(ImportErrors, ObjNumbersMustBeFiniteNumbers) {
    TempDir dir;
    for (const std::string bad : {"nan", "inf", "abc", "0x10", "-infinity", "1e999"}) {
        write_text(dir.file("bad.obj"), lit_obj(dir, "v " + bad + " 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n"));
        expect_rejected(dir.file("bad.obj"), "bad.obj:3", bad);
    }
}

TEST(ImportErrors, ObjIndicesMustBeInRange) {
    TempDir dir;
    write_text(dir.file("wrap.obj"), lit_obj(dir, std::string(kQuadObj) + "f 1 2 4294967299\n"));
    expect_rejected(dir.file("wrap.obj"), "wrap.obj:8", "out of range");
    write_text(dir.file("zero.obj"), lit_obj(dir, std::string(kQuadObj) + "f 0 1 2\n"));
    expect_rejected(dir.file("zero.obj"), "zero.obj:8", "out of range");
    write_text(dir.file("neg.obj"), lit_obj(dir, std::string(kQuadObj) + "f -5 1 2\n"));
    expect_rejected(dir.file("neg.obj"), "neg.obj:8", "out of range");
}

TEST(ImportErrors, MtlNamingAMissingTextureOrLibrary) {
    TempDir dir;
    write_text(dir.file("tex.obj"), lit_obj(dir, kQuadObj, "newmtl wood\nmap_Kd nowhere.png\n"));
    expect_rejected(dir.file("tex.obj"), "lit.mtl:5", "missing texture");
    write_text(dir.file("lib.obj"), std::string("mtllib gone.mtl\n") + kQuadObj);
    expect_rejected(dir.file("lib.obj"), "lib.obj:1", "missing material library");
}

// `mtllib` may name any file: an error in one that is no MTL names the file and the line and
// quotes none of its text.
TEST(ImportErrors, MtlErrorsQuoteNoneOfTheFile) {
    TempDir dir;
    write_text(dir.file("secret.txt"), "root:x:0:0:SECRET:/root:/bin/bash\n");
    write_text(dir.file("leak.obj"), std::string("mtllib secret.txt\n") + kQuadObj);
    expect_rejected(dir.file("leak.obj"), "secret.txt:1", "before any newmtl");
    write_text(dir.file("secret.mtl"), "newmtl a\nKd SECRET 0 0\n");
    write_text(dir.file("leak2.obj"), std::string("mtllib secret.mtl\n") + kQuadObj);
    expect_rejected(dir.file("leak2.obj"), "secret.mtl:2", "not a number");
    for (const char* obj : {"leak.obj", "leak2.obj"}) {
        ProgramResult r = run_program({"info", dir.file(obj)});
        EXPECT_EQ(r.err.find("SECRET"), std::string::npos) << r.err;
    }
}

// Several libraries on one line, each must exist; a library named twice is read once.
TEST(ImportErrors, MtllibOfSeveralNames) {
    TempDir dir;
    write_text(dir.file("many.obj"), lit_obj(dir, kQuadObj).replace(0, 14, "mtllib lit.mtl gone.mtl"));
    expect_rejected(dir.file("many.obj"), "many.obj:1", "missing material library: " + dir.file("gone.mtl"));
    // One name with a space in it is still one library.
    write_text(dir.file("my lit.mtl"), "newmtl lamp\nKe 1 1 1\n");
    write_text(dir.file("spaced.obj"), std::string("mtllib my lit.mtl\nusemtl lamp\n") + kQuadObj);
    ProgramResult r = run_program({"info", dir.file("spaced.obj")});
    EXPECT_EQ(r.exit_code, 0) << r.err;
}

// Emission far beyond any real light overflows the light's power (emission x area x pi) in
// single precision: as in a scene file, radiance above 1e30 is refused.
TEST(ImportErrors, MtlEmissionTooLarge) {
    TempDir dir;
    write_text(dir.file("sun.obj"), lit_obj(dir, kQuadObj, "newmtl sun\nKd 0 0 0\nKe 1e38 1e38 1e38\n") +
                                        "usemtl sun\nf 1 2 3\n");
    expect_rejected(dir.file("sun.obj"), "lit.mtl:6", "Ke is larger than 1e30");
}

TEST(ImportErrors, SceneWithoutAnyLight) {
    TempDir dir;
    write_text(dir.file("dark.obj"), kQuadObj);
    expect_rejected(dir.file("dark.obj"), "dark.obj", "no light");
}

// A valid emissive quad as .gltf + .bin, then broken in one place at a time.
nlohmann::json valid_gltf(const TempDir& dir) {
    ModelMesh m;
    m.quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
    write_gltf(dir.file("ok.gltf"), m, {{"lamp", Vec3(0), Vec3(1)}}, false);
    std::ifstream in(dir.file("ok.gltf"));
    return nlohmann::json::parse(in);
}

void expect_gltf_rejected(const TempDir& dir, const nlohmann::json& j, const std::string& what) {
    write_text(dir.file("bad.gltf"), j.dump());
    std::filesystem::copy_file(dir.file("ok.bin"), dir.file("bad.bin"), std::filesystem::copy_options::overwrite_existing);
    expect_rejected(dir.file("bad.gltf"), "bad.gltf", what);
}

TEST(ImportErrors, GltfFaults) {
    TempDir dir;
    const nlohmann::json ok = valid_gltf(dir);
    {
        ProgramResult r = run_program({"info", dir.file("ok.gltf")});
        ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    auto j = ok;
    j["buffers"][0]["uri"] = "missing.bin";
    expect_gltf_rejected(dir, j, "missing.bin");
    j = ok;
    j["accessors"][3]["count"] = 600;  // indices past the buffer's end
    expect_gltf_rejected(dir, j, "past the end");
    j = ok;
    j["accessors"][3]["byteOffset"] = 4;  // shifted: out of the view
    j["accessors"][3]["count"] = 6;
    expect_gltf_rejected(dir, j, "past the end");
    j = ok;
    j["meshes"][0]["primitives"][0]["indices"] = 42;
    expect_gltf_rejected(dir, j, "indices accessor");
    j = ok;
    j["meshes"][0]["primitives"][0]["mode"] = 1;  // lines
    expect_gltf_rejected(dir, j, "only triangles");
    j = ok;
    j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    expect_gltf_rejected(dir, j, "KHR_draco_mesh_compression");
    j = ok;
    j["images"] = {{{"uri", "missing.png"}}};
    j["textures"] = {{{"source", 0}}};
    j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    expect_gltf_rejected(dir, j, "missing.png");
    j = ok;
    j["materials"][0]["emissiveFactor"] = {0, 0, 0};
    expect_gltf_rejected(dir, j, "no light");
    // A scene that names the material for the file reads none of the file's materials, so an
    // image they would need may be missing.
    j = ok;
    j["images"] = {{{"uri", "missing.png"}}};
    j["textures"] = {{{"source", 0}}};
    j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    write_text(dir.file("bad.gltf"), j.dump());
    write_text(dir.file("scene.json"), R"({"camera": {"position": [0.5, 0.5, 2], "look_at": [0.5, 0.5, 0]},
        "materials": {"w": {"type": "diffuse"}},
        "shapes": [{"type": "gltf", "file": "bad.gltf", "material": "w"}],
        "lights": [{"type": "point", "position": [0, 0, 1], "power": [1, 1, 1]}]})");
    ProgramResult r = run_program({"info", dir.file("scene.json")});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
}

// Found by fuzzing: a binary glTF whose buffer claims 0 bytes beside a BIN chunk made tinygltf
// throw std::out_of_range out of its loader (the program ended with exit status 1).
// Sizes, offsets, strides and counts forged so that offset + count x stride wraps around 64
// bits (the old check passed, and the reader went on past the buffer into the heap).
TEST(ImportErrors, GltfForgedSizesWrapNoCheck) {
    TempDir dir;
    const nlohmann::json ok = valid_gltf(dir);
    auto j = ok;
    j["accessors"][0]["count"] = uint64_t(1) << 62;  // x 12 bytes = 3 x 2^64: "needs" 0 bytes
    expect_gltf_rejected(dir, j, "POSITION accessor 0: 4611686018427387904 elements of stride 12 overflow");
    j = ok;
    j["accessors"][0]["byteOffset"] = ~uint64_t(0) - 7;  // + 48 bytes wraps to 40
    expect_gltf_rejected(dir, j, "POSITION accessor 0 reaches past the end of its bufferView 0");
    j = ok;
    j["bufferViews"][1]["byteOffset"] = 16;
    j["bufferViews"][1]["byteLength"] = ~uint64_t(0) - 15;  // offset + length wraps to 0
    expect_gltf_rejected(dir, j, "bufferView 1 (of mesh 0 primitive 0: NORMAL accessor 1) reaches past the end of buffer 0");
    j = ok;
    j["bufferViews"][0]["byteStride"] = 4;  // each VEC3 of floats is 12 bytes
    expect_gltf_rejected(dir, j, "bufferView 0 (of mesh 0 primitive 0: POSITION accessor 0): byteStride 4 is smaller");
    j = ok;  // an image inside a view that claims 100 MB of a buffer of a few hundred bytes
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 100000000}});
    j["images"] = {{{"bufferView", j["bufferViews"].size() - 1}, {"mimeType", "image/png"}}};
    expect_gltf_rejected(dir, j, "image 0: its bufferView 4 reaches past the end of its buffer");
}

// 100,000 nested arrays or objects in `extras` overflowed the stack inside tinygltf (which
// converts them recursively) before any check of ours: the JSON text's depth is scanned first.
TEST(ImportErrors, GltfNestedTooDeep) {
    TempDir dir;
    const std::string ok = valid_gltf(dir).dump();
    const std::string arrays = std::string(100000, '[') + std::string(100000, ']');
    std::string objects;
    for (int i = 0; i < 100000; ++i) objects += "{\"a\":";
    objects += "1" + std::string(100000, '}');
    for (const std::string& deep : {arrays, objects}) {
        std::string text = ok;
        text.insert(1, "\"extras\":" + deep + ",");
        write_text(dir.file("deep.gltf"), text);
        std::filesystem::copy_file(dir.file("ok.bin"), dir.file("deep.bin"), std::filesystem::copy_options::overwrite_existing);
        expect_rejected(dir.file("deep.gltf"), "deep.gltf", "its JSON is nested more than 64 levels deep");
    }
    // Brackets inside strings do not count; 64 levels (the file's object, extras, 62 arrays) are fine.
    std::string text = ok;
    text.insert(1, "\"extras\":{\"s\":\"" + arrays + "\",\"d\":" + std::string(62, '[') + std::string(62, ']') + "},");
    write_text(dir.file("fine.gltf"), text);
    std::filesystem::copy_file(dir.file("ok.bin"), dir.file("fine.bin"), std::filesystem::copy_options::overwrite_existing);
    ProgramResult r = run_program({"info", dir.file("fine.gltf")});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    // The same in a .glb's JSON chunk (its buffer the .bin beside it).
    text = ok;
    text.insert(1, "\"extras\":" + arrays + ",");
    while (text.size() % 4) text.push_back(' ');
    std::ofstream glb(dir.file("deep.glb"), std::ios::binary);
    auto u32 = [&](uint32_t v) { glb.write(reinterpret_cast<const char*>(&v), 4); };
    glb.write("glTF", 4);
    u32(2);
    u32(static_cast<uint32_t>(20 + text.size()));
    u32(static_cast<uint32_t>(text.size()));
    glb.write("JSON", 4);
    glb << text;
    glb.close();
    expect_rejected(dir.file("deep.glb"), "deep.glb", "its JSON is nested more than 64 levels deep");
}

// An emissive strength or a light intensity of 1e38 overflowed the light's power (and the
// program aborted inside Embree): bounded as a scene file's lights are, at 1e30.
TEST(ImportErrors, GltfEmissionOrIntensityTooLarge) {
    TempDir dir;
    const nlohmann::json ok = valid_gltf(dir);
    auto j = ok;
    j["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = 1e38;
    expect_gltf_rejected(dir, j, "material 'lamp': the emission (emissiveFactor x emissiveStrength) is larger than 1e30");
    for (const char* type : {"point", "spot", "directional"}) {
        SCOPED_TRACE(type);
        j = ok;
        j["extensionsUsed"].push_back("KHR_lights_punctual");
        j["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", type}, {"name", "flash"}, {"intensity", 1e38}}};
        if (std::string(type) == "spot") j["extensions"]["KHR_lights_punctual"]["lights"][0]["spot"] = nlohmann::json::object();
        j["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
        j["scenes"][0]["nodes"].push_back(1);
        expect_gltf_rejected(dir, j, std::string("light 0 ('flash'): its ") +
                                         (std::string(type) == "directional" ? "irradiance" : "power") +
                                         " (colour x intensity) is larger than 1e30");
    }
}

// Each material's emission is bounded, not the area it covers: the sum is checked too.
TEST(ImportErrors, EmissiveTrianglesOfOverflowingPower) {
    TempDir dir;
    write_text(dir.file("big.mtl"), "newmtl sun\nKd 0 0 0\nKe 1e30 1e30 1e30\n");
    write_text(dir.file("big.obj"), "mtllib big.mtl\nusemtl sun\nv 0 0 0\nv 100000 0 0\nv 100000 100000 0\n"
                                    "v 0 100000 0\nf 1 2 3 4\n");
    expect_rejected(dir.file("big.obj"), "big.obj", "the emissive triangles' power (emission times area) is too large");
}

TEST(ImportErrors, GltfBinaryBufferOfZeroBytes) {
    TempDir dir;
    std::string json = R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":0}]})";
    while (json.size() % 4) json += ' ';
    const std::string bin(8, '\0');
    auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    const std::string glb = "glTF" + u32(2) + u32(static_cast<uint32_t>(12 + 8 + json.size() + 8 + bin.size())) +
                            u32(static_cast<uint32_t>(json.size())) + "JSON" + json +
                            u32(static_cast<uint32_t>(bin.size())) + std::string("BIN\0", 4) + bin;
    std::ofstream(dir.file("zero.glb"), std::ios::binary) << glb;
    expect_rejected(dir.file("zero.glb"), "zero.glb", "out of range");
}

TEST(ImportErrors, GltfIndexOutOfRangeAndNonFiniteVertex) {
    TempDir dir;
    ModelMesh m;
    m.quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
    m.indices[4] = 7;  // only 4 vertices
    write_gltf(dir.file("idx.glb"), m, {{"lamp", Vec3(0), Vec3(1)}}, true);
    expect_rejected(dir.file("idx.glb"), "idx.glb", "index 7 is out of range");
    ModelMesh n;
    n.quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
    n.positions[2].x = std::numeric_limits<float>::quiet_NaN();
    write_gltf(dir.file("nan.glb"), n, {{"lamp", Vec3(0), Vec3(1)}}, true);
    expect_rejected(dir.file("nan.glb"), "nan.glb", "not finite");
}

TEST(ImportErrors, ApproximationsWarnOncePerMaterial) {
    TempDir dir;
    nlohmann::json j = valid_gltf(dir);
    j["materials"][0]["alphaMode"] = "BLEND";
    j["materials"][0]["extensions"]["KHR_materials_ior"] = {{"ior", 0.5}};  // (normal maps are drawn now)
    write_text(dir.file("ok.gltf"), j.dump());
    ProgramResult r = run_program({"info", dir.file("ok.gltf")});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    size_t first = r.err.find("warning: ");
    ASSERT_NE(first, std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("warning: ", first + 1), std::string::npos) << r.err;  // one line for the material
    EXPECT_NE(r.err.find("material 'lamp'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("alpha BLEND"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("ior outside"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace sl::test
