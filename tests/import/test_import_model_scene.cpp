// `slowlight render model.glb` without a scene file: the file's camera and lights (point and
// spot intensity in candela, cd / 683 = W/sr; or W/sr as written when radiometric), or a camera that frames the scene, and a time window for light
// to cross it three times.
#include <gtest/gtest.h>

#include <cmath>

#include "config/parse_scene.h"
#include "core/camera.h"
#include "core/import/resolve_imports.h"
#include "foundation/errors.h"
#include "core/import/model_scene.h"
#include "tests/common/temp_dir.h"
#include "tests/import/model_writers.h"
#include "tests/render/render_helpers.h"

namespace sl::test {
namespace {

// A 4 x 4 m floor (albedo 0.5) at y = 0, a light 2 m above its middle and a camera looking down.
nlohmann::json lights_and_camera(const std::string& type, double intensity) {
    nlohmann::json light = {{"type", type}, {"intensity", intensity}, {"color", {1.0, 1.0, 1.0}}};
    if (type == "spot") light["spot"] = {{"innerConeAngle", 0.3}, {"outerConeAngle", 0.5}};
    // Pointing down: -z rotated onto -y is a rotation of -90 degrees about x.
    const double s = std::sqrt(0.5);
    return {{"lights", {light}},
            {"nodes",
             {{{"translation", {0, 2, 0}}, {"rotation", {-s, 0, 0, s}},
               {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
              {{"translation", {0, 3, 0}}, {"rotation", {-s, 0, 0, s}}, {"camera", 0}}}}};
}

void write_floor_model(const std::string& path, const std::string& type, double intensity) {
    ModelMesh m;
    m.quad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, 0);
    write_gltf(path, m, {{"floor", Vec3(0.5f)}}, true, lights_and_camera(type, intensity));
    // Add the camera the writer does not know about.
    std::ifstream in(path, std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    uint32_t json_len;
    std::memcpy(&json_len, bytes.data() + 12, 4);
    auto j = nlohmann::json::parse(std::string(bytes.data() + 20, json_len));
    j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 1.2}, {"znear", 0.01}, {"aspectRatio", 1.0}}}}};
    std::vector<unsigned char> bin(bytes.begin() + 20 + json_len + 8, bytes.end());
    std::string text = j.dump();
    while (text.size() % 4) text.push_back(' ');
    std::ofstream o(path, std::ios::binary);
    auto u32 = [&](uint32_t v) { o.write(reinterpret_cast<const char*>(&v), 4); };
    o.write("glTF", 4);
    u32(2);
    u32(static_cast<uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
    u32(static_cast<uint32_t>(text.size()));
    o.write("JSON", 4);
    o.write(text.data(), static_cast<std::streamsize>(text.size()));
    u32(static_cast<uint32_t>(bin.size()));
    o.write("BIN\0", 4);
    o.write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
}

// The middle pixel of a direct-light-only render of the model: radiance 0.5/pi * I / h^2.
double centre_radiance(const std::string& file) {
    SceneDesc s = scene_for_model(file);
    s.camera.width = s.camera.height = 16;
    s.render.max_depth = 1;
    s.render.passes = 16;
    s.render.photons_per_pass = 100;
    const Rendered r = render_all(s);
    double sum = 0;
    for (int y = 7; y <= 8; ++y)
        for (int x = 7; x <= 8; ++x) sum += r.steady[(static_cast<size_t>(y) * 16 + x) * 3];
    return sum / 4;
}

TEST(ImportModelScene, PointAndSpotIntensityAreCandelaAt683LumensPerWatt) {
    TempDir dir;
    const double I = 20, h = 2;  // W/sr
    write_floor_model(dir.file("point.glb"), "point", I * 683);
    SceneDesc s = scene_for_model(dir.file("point.glb"));
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_NEAR(s.lights[0].power.x, 4 * M_PI * I, 1e-3);
    // The file's camera: 3 m up, looking down, 1.2 rad field of view.
    EXPECT_NEAR(s.camera.position.y, 3, 1e-5);
    EXPECT_NEAR(s.camera.look_at.y, 2, 1e-5);
    EXPECT_NEAR(s.camera.vfov_deg, 1.2 * 180 / M_PI, 1e-3);
    // The four middle pixels see the floor within +-a of the middle (camera 3 m up, 16 pixels
    // over 2 * 3 tan(0.6)): their mean of 0.5/pi * I cos/r^2 over that square.
    const double a = 3 * std::tan(0.6) / 8;
    double expected = 0;
    const int n = 200;
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < n; ++k) {
            double x = a * (2 * (i + 0.5) / n - 1), z = a * (2 * (k + 0.5) / n - 1), r2 = x * x + z * z + h * h;
            expected += 0.5 / M_PI * I * h / (r2 * std::sqrt(r2)) / (n * n);
        }
    EXPECT_NEAR(centre_radiance(dir.file("point.glb")), expected, 0.01 * expected);
    write_floor_model(dir.file("spot.glb"), "spot", I * 683);
    SceneDesc sp = scene_for_model(dir.file("spot.glb"));
    ASSERT_EQ(sp.lights.size(), 1u);
    EXPECT_EQ(sp.lights[0].type, LightType::Spot);
    EXPECT_NEAR(sp.lights[0].cone_deg, 0.4 * 180 / M_PI, 1e-3);  // half-way between the cones
    EXPECT_NEAR(centre_radiance(dir.file("spot.glb")), expected, 0.01 * expected);
}

// Blender's default ("Standard") lighting mode writes a 100 W point light as 100 / (4 pi) * 683
// = 5435.2 cd: it must come back as (nearly) 100 W, and exactly 4 pi * 5435.2 / 683.
TEST(ImportModelScene, A5435CandelaPointIsA100WattPoint) {
    TempDir dir;
    write_floor_model(dir.file("point.glb"), "point", 5435.2);
    SceneDesc s = scene_for_model(dir.file("point.glb"));
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].type, LightType::Point);
    EXPECT_FLOAT_EQ(s.lights[0].power.x, static_cast<float>(4 * M_PI * 5435.2 / 683));
    EXPECT_NEAR(s.lights[0].power.y, 100, 0.01);
    // Explicitly photometric: the same.
    EXPECT_FLOAT_EQ(scene_for_model(dir.file("point.glb"), LightUnits::Photometric).lights[0].power.z,
                    static_cast<float>(4 * M_PI * 5435.2 / 683));
}

// Files in radiometric units (Blender's "Unitless" mode): the number is W/sr, as before.
TEST(ImportModelScene, RadiometricUnitsReadTheIntensityAsWattsPerSteradian) {
    TempDir dir;
    const double I = 20;
    write_floor_model(dir.file("point.glb"), "point", I);
    SceneDesc s = scene_for_model(dir.file("point.glb"), LightUnits::Radiometric);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_FLOAT_EQ(s.lights[0].power.x, static_cast<float>(4 * M_PI * I));
    write_floor_model(dir.file("spot.glb"), "spot", I);
    SceneDesc sp = scene_for_model(dir.file("spot.glb"), LightUnits::Radiometric);
    ASSERT_EQ(sp.lights.size(), 1u);
    const double cone = 0.4;  // half-way between the file's cones: a hard cone of that half-angle
    EXPECT_NEAR(sp.lights[0].power.x, I * 2 * M_PI * (1 - std::cos(cone)), 1e-4);
    SceneDesc sp_cd = scene_for_model(dir.file("spot.glb"));
    EXPECT_NEAR(sp_cd.lights[0].power.x, I / 683 * 2 * M_PI * (1 - std::cos(cone)), 1e-7);
}

// In a scene file: the gltf shape's "light_units", and --gltf-light-units as the default for the
// shapes that do not say.
TEST(ImportModelScene, SceneFileLightUnitsKeyAndCommandLineDefault) {
    TempDir dir;
    write_floor_model(dir.file("point.glb"), "point", 20);
    const std::string text = R"({"camera": {"position": [0, 3, 0], "look_at": [0, 0, 1]}, "shapes": [
        {"type": "gltf", "file": "point.glb"},
        {"type": "gltf", "file": "point.glb", "light_units": "radiometric"},
        {"type": "gltf", "file": "point.glb", "light_units": "photometric"}]})";
    auto powers = [&](std::optional<LightUnits> flag) {
        SceneDesc s = parse_scene_text(text, "scene.json", dir.path().string());
        apply_gltf_light_units(s, flag);
        resolve_imports(s);
        std::vector<float> p;
        for (const LightDesc& l : s.lights) p.push_back(l.power.x);
        return p;
    };
    const float cd = static_cast<float>(4 * M_PI * 20 / 683), wsr = static_cast<float>(4 * M_PI * 20);
    const std::vector<float> no_flag = powers(std::nullopt), radiometric = powers(LightUnits::Radiometric);
    ASSERT_EQ(no_flag.size(), 3u);
    ASSERT_EQ(radiometric.size(), 3u);
    EXPECT_FLOAT_EQ(no_flag[0], cd);
    EXPECT_FLOAT_EQ(no_flag[1], wsr);
    EXPECT_FLOAT_EQ(no_flag[2], cd);
    EXPECT_FLOAT_EQ(radiometric[0], wsr);  // the flag: the default of the shape without the key
    EXPECT_FLOAT_EQ(radiometric[1], wsr);
    EXPECT_FLOAT_EQ(radiometric[2], cd);   // the shape's own key wins
    // Anything else is refused, naming the key; a mesh (OBJ) has no such key.
    try {
        parse_scene_text(R"({"camera": {"position": [0, 3, 0], "look_at": [0, 0, 1]},
                             "shapes": [{"type": "gltf", "file": "point.glb", "light_units": "lumens"}]})",
                         "scene.json", dir.path().string());
        ADD_FAILURE() << "accepted light_units lumens";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("light_units"), std::string::npos) << e.what();
    }
}

TEST(ImportModelScene, WithoutCameraTheSceneIsFramedAndTheTimeCoversThreeCrossings) {
    TempDir dir;
    ModelMesh m;
    m.box({-3, -1, -2}, {5, 2, 0.5f}, 0);
    m.quad({-0.5f, 1.9f, -0.5f}, {1, 0, 0}, {0, 0, 1}, 1);
    write_obj(dir.file("room.obj"), "room.mtl", m, {{"wall", Vec3(0.5f)}, {"lamp", Vec3(0), Vec3(3)}});
    SceneDesc s = scene_for_model(dir.file("room.obj"));
    const double diagonal = std::sqrt(8.0 * 8 + 3 * 3 + 2.5 * 2.5);
    EXPECT_NEAR(s.time.end_ns - s.time.start_ns, 3 * diagonal / 0.299792458, 1e-3);
    PinholeCamera cam(s.camera);
    // Every corner of the bounds is in view.
    for (int c = 0; c < 8; ++c) {
        Vec3 p{c & 1 ? 5.0f : -3.0f, c & 2 ? 2.0f : -1.0f, c & 4 ? 0.5f : -2.0f};
        Vec3 d = normalize(p - cam.position());
        const float cos_half = std::cos(20 * 3.14159265f / 180);  // the framing camera's 40 degrees
        const float along = dot(d, cam.forward());
        EXPECT_GT(along, 0);
        Vec3 right = normalize(cross(cam.forward(), Vec3(0, 1, 0)));
        Vec3 up = cross(right, cam.forward());
        EXPECT_LE(std::abs(dot(d, up)) / along, std::tan(std::acos(cos_half)) + 1e-4) << c;
        EXPECT_LE(std::abs(dot(d, right)) / along, std::tan(std::acos(cos_half)) + 1e-4) << c;
    }
}

}  // namespace
}  // namespace sl::test
