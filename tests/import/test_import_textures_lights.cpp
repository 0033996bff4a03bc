// Emission textures, the texture plugin loaded only when a texture is used, and glTF
// directional lights becoming suns (lux / 683 = W/m^2, or W/m^2 as written when radiometric).
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "core/import/model_scene.h"
#include "core/import/resolve_imports.h"
#include "stages/output/png_io.h"
#include "tests/common/temp_dir.h"
#include "tests/import/model_writers.h"
#include "tests/pipeline/run_program.h"
#include "tests/render/render_helpers.h"
#include "tests/render/scenes_for_tests.h"

namespace sl::test {
namespace {

SceneDesc floor_with_panel(const std::string& obj) {
    SceneDesc s = plane_under_point_light(0.7f, 0, 1, 1.5f, 16, 2);
    s.lights.clear();
    s.render.passes = 4;
    s.render.photons_per_pass = 5000;
    s.time = {0, 12, 4, 24};
    s.shapes.push_back(model_shape(obj));
    return s;
}

TEST(ImportTextures, EmissionTextureScalesTheEmission) {
    TempDir dir;
    std::vector<uint8_t> grey(4 * 4 * 3, 128);
    write_png(dir.file("glow.png"), 4, 4, grey.data());
    const double texel = std::pow((128 / 255.0 + 0.055) / 1.055, 2.4);  // sRGB 128, linear
    // A panel facing down at 1 m: Ke 10 with the texture, against Ke 10 x texel without.
    auto panel = [&](const std::string& name, const std::string& mtl) {
        std::ofstream(dir.file(name + ".obj")) << "mtllib " << name << ".mtl\nusemtl lamp\n"
                                               << "v -0.25 1 -0.2\nv -0.25 1 0.2\nv 0.25 1 0.2\nv 0.25 1 -0.2\n"
                                               << "vt 0 0\nvt 0 1\nvt 1 1\nvt 1 0\nf 1/1 2/2 3/3 4/4\n";
        std::ofstream(dir.file(name + ".mtl")) << "newmtl lamp\nKd 0 0 0\n" << mtl;
        return dir.file(name + ".obj");
    };
    const Rendered textured = render_all(floor_with_panel(panel("tex", "Ke 10 10 10\nmap_Ke glow.png\n")));
    std::ostringstream ke;
    ke.precision(9);
    ke << "Ke " << 10 * texel << ' ' << 10 * texel << ' ' << 10 * texel << "\n";
    const Rendered plain = render_all(floor_with_panel(panel("plain", ke.str())));
    ASSERT_GT(mean(plain.steady), 0);
    EXPECT_NEAR(mean(textured.steady), mean(plain.steady), 1e-4 * mean(plain.steady));
}

// True when OpenImageIO's texture plugin is mapped into this process.
bool texture_plugin_loaded() {
    std::ifstream maps("/proc/self/maps");
    std::string line;
    while (std::getline(maps, line))
        if (line.find("libslowlight_image") != std::string::npos) return true;
    return false;
}

// Run in a fresh copy of this test program (SL_PROBE_OBJ set): resolves the OBJ's scene and
// exits with 1 when that loaded the texture plugin, 0 when not.
TEST(ImportTextures, ChildProbe) {
    const char* obj = std::getenv("SL_PROBE_OBJ");
    if (!obj) GTEST_SKIP() << "run by PluginLoadsOnlyForTexturedScenes";
    SceneDesc s = floor_with_panel(obj);
    resolve_imports(s);
    std::fflush(stdout);
    _exit(texture_plugin_loaded() ? 1 : 0);
}

bool plugin_loaded_by(const std::string& obj) {
    char self[4096];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n <= 0) return false;
    setenv("SL_PROBE_OBJ", obj.c_str(), 1);
    ProgramResult r = run_program({"--gtest_filter=ImportTextures.ChildProbe"}, "", 60, std::string(self, static_cast<size_t>(n)));
    unsetenv("SL_PROBE_OBJ");
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.err;
    return r.exit_code == 1;
}

TEST(ImportTextures, PluginLoadsOnlyForTexturedScenes) {
    TempDir dir;
    std::vector<uint8_t> grey(2 * 2 * 3, 100);
    write_png(dir.file("t.png"), 2, 2, grey.data());
    ModelMesh m;
    m.quad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0);
    m.quad({-0.2f, 1, -0.2f}, {0, 0, 0.4f}, {0.4f, 0, 0}, 1);
    write_obj(dir.file("plain.obj"), "plain.mtl", m, {{"floor", Vec3(0.5f)}, {"lamp", Vec3(0), Vec3(5)}});
    write_obj(dir.file("tex.obj"), "tex.mtl", m, {{"floor", Vec3(0.5f), Vec3(0), "t.png"}, {"lamp", Vec3(0), Vec3(5)}});
    EXPECT_FALSE(plugin_loaded_by(dir.file("plain.obj")));
    EXPECT_TRUE(plugin_loaded_by(dir.file("tex.obj")));
    // A texture of a material no triangle uses is never decoded.
    SceneDesc s = floor_with_panel(dir.file("tex.obj"));
    resolve_imports(s);
    EXPECT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(texture_bytes(s), 2u * 2 * 4);  // 8-bit RGBA
}

// The irradiance of the one sun of a model, read in the given units.
float sun_irradiance(const std::string& file, std::optional<LightUnits> units) {
    SceneDesc s = scene_for_model(file, units);
    float e = -1;
    for (const LightDesc& l : s.lights)
        if (l.type == LightType::Sun) e = l.irradiance.x;
    return e;
}

TEST(ImportLights, DirectionalLightBecomesASunOfItsIlluminanceOver683) {
    TempDir dir;
    ModelMesh m;
    m.quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
    // 2049 lux: what Blender's default ("Standard") lighting mode writes for a 3 W/m^2 sun.
    nlohmann::json lights = {{"lights", {{{"type", "directional"}, {"name", "sun"}, {"intensity", 2049.0}}}},
                             {"nodes", {{{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}}}};
    write_gltf(dir.file("sun.glb"), m, {{"lamp", Vec3(0), Vec3(1)}}, true, lights);
    EXPECT_FLOAT_EQ(sun_irradiance(dir.file("sun.glb"), LightUnits::Photometric), 3.0f);
    // Read as W/m^2 (Blender's "Unitless" mode), the number is the irradiance.
    EXPECT_FLOAT_EQ(sun_irradiance(dir.file("sun.glb"), LightUnits::Radiometric), 2049.0f);
    SceneDesc s = scene_for_model(dir.file("sun.glb"));
    resolve_imports(s);
    int suns = 0;
    for (const LightDesc& l : s.lights) {
        if (l.type != LightType::Sun) continue;
        ++suns;
        EXPECT_FLOAT_EQ(l.irradiance.x, 3.0f);  // photometric by default: 2049 lux / 683
        EXPECT_NEAR(l.direction.z, -1.0f, 1e-6f);  // a node without rotation shines along -Z
        EXPECT_EQ(l.angle_deg, 0.0f);
    }
    EXPECT_EQ(suns, 1);
    ProgramResult r = run_program({"info", dir.file("sun.glb")});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.find("directional"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace sl::test
