// Mistakes that once ended in a silent black video with exit status 0 now get a `warning:` line
// (and still exit 0): a time window that closes before any reflected light arrives, a light
// outside the closed room the camera is in, a scene whose size says its coordinates are not
// meters, a render where no light reaches the camera, and a glTF file whose lamps and emissive
// surfaces differ so much in power that one of them is in the other unit. Each fires on its case
// and on none of the samples. `info` states the numbers behind them (every light's watts too).
#include <gtest/gtest.h>

#include <cmath>
#include <regex>

#include "tests/import/model_writers.h"
#include "tests/pipeline/pipeline_helpers.h"

using namespace sl;
using namespace sl::test;

namespace {

nlohmann::json box() { return read_json(sample("cornell_box.json")); }

std::string write_scene(const ScratchDir& dir, const std::string& name, const nlohmann::json& scene) {
    const std::string path = dir.file(name);
    std::ofstream(path) << scene.dump(1);
    return path;
}

std::vector<std::string> warnings(const std::string& err) {
    std::vector<std::string> w;
    std::istringstream lines(err);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("warning:", 0) == 0) w.push_back(line);
    return w;
}

// `info SCENE`: its warnings (stderr) and its text (stdout).
std::vector<std::string> info_warnings(const ScratchDir& dir, const std::string& scene, std::string* text = nullptr) {
    const std::string out = dir.file("info.txt");
    ProgramResult r = run_program({"info", scene}, out);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    if (text) *text = read_text(out);
    return warnings(r.err);
}

// Scales every length of a scene by `k` (camera, shapes, lights), leaving units out.
void scale_lengths(nlohmann::json& j, double k) {
    for (const char* key : {"position", "look_at", "corner", "edge1", "edge2", "min", "max", "center"})
        if (j.contains(key) && j[key].is_array())
            for (auto& v : j[key]) v = v.get<double>() * k;
    if (j.contains("radius") && j["radius"].is_number()) j["radius"] = j["radius"].get<double>() * k;
    for (auto& [key, value] : j.items())
        if (value.is_object() || value.is_array()) {
            if (value.is_array())
                for (auto& e : value)
                    if (e.is_object()) scale_lengths(e, k);
            if (value.is_object()) scale_lengths(value, k);
        }
}

}  // namespace

TEST(SceneWarnings, NoneForAnySample) {
    ScratchDir dir;
    for (const std::string& scene : sample_scenes()) {
        SCOPED_TRACE(scene);
        EXPECT_TRUE(info_warnings(dir, scene).empty());
        // And the render, whose black-video check runs after the last section.
        ProgramResult r = run_program(small_render(scene, {"--exr-dir", dir.file("exr")}, 2, 1, 2000, 24, 24));
        SL_EXPECT_EXIT(r, 0);
        EXPECT_TRUE(warnings(r.err).empty()) << r.err;
    }
}

// The box's end_ns before the first reflected light: the lamp is 0.78 m above the short box's
// top... which the camera cannot see; the earliest surface it sees lit is the left wall's top
// near the lamp. The warning states a time between the nearest lit surface and end_ns.
TEST(SceneWarnings, TimeWindowEndsBeforeAnyReflectedLight) {
    ScratchDir dir;
    nlohmann::json s = box();
    s["time"]["end_ns"] = 1.0;
    s["time"]["frames"] = 4;
    std::vector<std::string> w = info_warnings(dir, write_scene(dir, "early.json", s));
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("end_ns"), std::string::npos) << w[0];
    std::smatch m;
    ASSERT_TRUE(std::regex_search(w[0], m, std::regex(R"(arrives at about ([0-9.]+) ns)"))) << w[0];
    const double first = std::stod(m[1]);
    // The lamp (y = 1.98, x in [-0.25, 0.25]) to the side walls (x = +-1) is at least 0.75 m: 2.5 ns;
    // nothing the camera sees is farther than the floor's far corners, 2.9 m: 9.7 ns.
    EXPECT_GE(first, 0.75 / 0.299792458 * 0.99);
    EXPECT_LE(first, 2.9 / 0.299792458);
    // The same scene with a window that reaches it: no warning, and a render still exits 0.
    s["time"]["end_ns"] = first * 1.05;
    EXPECT_TRUE(info_warnings(dir, write_scene(dir, "enough.json", s)).empty());
    s["time"]["end_ns"] = 1.0;
    ProgramResult r = run_program(small_render(write_scene(dir, "early.json", s), {"--exr-dir", dir.file("e")}, 4, 1, 1000, 16, 16));
    SL_EXPECT_EXIT(r, 0);
    EXPECT_EQ(warnings(r.err).size(), 1u) << r.err;
}

TEST(SceneWarnings, LightOutsideTheClosedRoom) {
    ScratchDir dir;
    nlohmann::json s = box();
    // Close the box's open front (z = 1) and put the camera inside it.
    s["shapes"].push_back({{"type", "quad"}, {"corner", {-1, 0, 1}}, {"edge1", {0, 2, 0}}, {"edge2", {2, 0, 0}},
                           {"material", "white"}});
    s["camera"]["position"] = {0, 1, 0.9};
    s["camera"]["vfov_deg"] = 60;
    const std::string inside = write_scene(dir, "closed.json", s);
    EXPECT_TRUE(info_warnings(dir, inside).empty()) << "the lamp inside the closed room";

    s["lights"] = nlohmann::json::array({{{"type", "point"}, {"position", {0, 2.5, 0}}, {"power", {50, 50, 50}}}});
    std::vector<std::string> w = info_warnings(dir, write_scene(dir, "outside.json", s));
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("lights[0] is outside the closed room"), std::string::npos) << w[0];
    ProgramResult r = run_program(small_render(dir.file("outside.json"), {"--exr-dir", dir.file("o")}, 2, 1, 1000, 16, 16));
    SL_EXPECT_EXIT(r, 0);
    EXPECT_NE(r.err.find("is outside the closed room"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("warning: " + dir.file("outside.json") + ": no light reached the camera"), std::string::npos)
        << r.err;
}

// The box written in centimeters without "units": 200 m across as meters, a crossing time of
// about 1000 ns against a 24 ns video.
TEST(SceneWarnings, SizeSuggestsWrongUnits) {
    ScratchDir dir;
    nlohmann::json s = box();
    scale_lengths(s, 100);
    std::string text;
    std::vector<std::string> w = info_warnings(dir, write_scene(dir, "cm.json", s), &text);
    ASSERT_FALSE(w.empty());
    EXPECT_NE(w[0].find("meters_per_unit\": 0.01"), std::string::npos) << w[0];
    // info's own numbers: the box's diagonal, sqrt(3) * 200 = 346.41 m, crossed in 346.41 / 0.29979 = 1155.50 ns.
    EXPECT_NE(text.find("200.000 x 200.000 x 200.000 m"), std::string::npos) << text;
    EXPECT_NE(text.find("in 1155.50 ns"), std::string::npos) << text;
    // With the units stated, the same file is the 2 m box again, without warnings.
    s["units"] = {{"meters_per_unit", 0.01}};
    EXPECT_TRUE(info_warnings(dir, write_scene(dir, "cm_units.json", s), &text).empty());
    EXPECT_NE(text.find("2.000 x 2.000 x 2.000 m"), std::string::npos) << text;
}

// A spot light behind the camera, pointing away from the open box: every frame black.
TEST(SceneWarnings, NoLightReachesTheCamera) {
    ScratchDir dir;
    nlohmann::json s = box();
    s["lights"] = nlohmann::json::array({{{"type", "spot"}, {"position", {0, 1, 4}}, {"direction", {0, 0, 1}},
                                          {"cone_deg", 30}, {"power", {100, 100, 100}}}});
    const std::string scene = write_scene(dir, "away.json", s);
    ProgramResult r = run_program(small_render(scene, {"--exr-dir", dir.file("exr")}, 2, 1, 2000, 16, 16));
    SL_EXPECT_EXIT(r, 0);
    std::vector<std::string> w = warnings(r.err);
    ASSERT_EQ(w.size(), 1u) << r.err;
    EXPECT_NE(w[0].find("no light reached the camera"), std::string::npos) << w[0];
    // info sees it coming: no light shines on anything the camera sees.
    std::string text;
    info_warnings(dir, scene, &text);
    EXPECT_NE(text.find("no light shines straight on anything the camera sees"), std::string::npos) << text;
}

TEST(SceneInfo, StatesSizeCrossingArrivalsAndTriangles) {
    ScratchDir dir;
    std::string text;
    info_warnings(dir, sample("cornell_box.json"), &text);
    // 5 wall quads, a lamp quad and 2 boxes of 6 quads: 18 quads, 36 triangles.
    EXPECT_NE(text.find("36 triangles"), std::string::npos) << text;
    EXPECT_NE(text.find("2.000 x 2.000 x 2.000 m"), std::string::npos) << text;
    // sqrt(12) m = 3.4641 m at 0.299792458 m/ns: 11.55 ns.
    EXPECT_NE(text.find("3.464 m in 11.55 ns"), std::string::npos) << text;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(text, m, std::regex(R"(arrives from ([0-9.]+) ns.*by ([0-9.]+) ns)"))) << text;
    const double first = std::stod(m[1]), last = std::stod(m[2]);
    EXPECT_GT(first, 0.5);
    EXPECT_LT(first, last);
    // The farthest visible point lit straight from the lamp (a floor corner at the front) is
    // under sqrt(1.25^2 + 2^2 + 1.2^2) = 2.65 m away: 8.9 ns.
    EXPECT_LE(last, 2.65 / 0.299792458 * 1.01);
}

namespace {

// A 1 m x 1 m emissive quad (radiance 1 W sr^-1 m^-2 from its front: pi W) and a point light
// 1 m in front of it of `intensity` (cd, or W/sr when the file is radiometric), and a sun of
// `sun_lux` (none when 0).
std::string write_lamp_and_panel(const ScratchDir& dir, const std::string& name, double intensity, double sun_lux = 0) {
    ModelMesh m;
    m.quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
    nlohmann::json lights = nlohmann::json::array({{{"type", "point"}, {"intensity", intensity}}});
    nlohmann::json nodes = nlohmann::json::array(
        {{{"translation", {0.5, 0.5, 1}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}});
    if (sun_lux > 0) {
        lights.push_back({{"type", "directional"}, {"intensity", sun_lux}});
        nodes.push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    }
    write_gltf(dir.file(name), m, {{"panel", Vec3(0.5f), Vec3(1)}}, true, {{"lights", lights}, {"nodes", nodes}});
    return dir.file(name);
}

std::vector<std::string> scale_warnings(const std::vector<std::string>& w) {
    std::vector<std::string> r;
    for (const std::string& line : w)
        if (line.find("almost certainly in the other unit") != std::string::npos) r.push_back(line);
    return r;
}

std::vector<std::string> info_warnings_with(const ScratchDir& dir, std::vector<std::string> args, std::string* text = nullptr) {
    const std::string out = dir.file("info.txt");
    args.insert(args.begin(), "info");
    ProgramResult r = run_program(args, out);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    if (text) *text = read_text(out);
    return warnings(r.err);
}

}  // namespace

TEST(SceneInfo, PrintsEveryLightsPowerInWatts) {
    ScratchDir dir;
    std::string text;
    info_warnings(dir, sample("cornell_box.json"), &text);
    // The lamp quad: pi x the mean of its radiance x its area.
    const nlohmann::json lamp = box()["lights"][0];
    auto v = [](const nlohmann::json& a) { return Vec3(a[0].get<float>(), a[1].get<float>(), a[2].get<float>()); };
    const Vec3 L = v(lamp["radiance"]);
    const double watts = M_PI * (double(L.x) + L.y + L.z) / 3 * length(cross(v(lamp["edge1"]), v(lamp["edge2"])));
    char expected[64];
    std::snprintf(expected, sizeof expected, "lights[0] quad: %.4g W", watts);
    EXPECT_NE(text.find(expected), std::string::npos) << expected << "\n" << text;

    // A glTF's point light of 5435.2 cd is 100 W; its 2049 lux sun 3 W/m^2; its emissive panel pi W.
    const std::string model = write_lamp_and_panel(dir, "lamp.glb", 5435.2, 2049);
    info_warnings_with(dir, {model}, &text);
    EXPECT_NE(text.find("lights[0] point: 100 W (from "), std::string::npos) << text;
    EXPECT_NE(text.find("lights[1] sun: 3 W/m^2, "), std::string::npos) << text;
    EXPECT_NE(text.find("emissive surfaces of " + model + ": 3.142 W"), std::string::npos) << text;
    // Read as radiometric, the same numbers are 683 times more.
    info_warnings_with(dir, {model, "--gltf-light-units", "radiometric"}, &text);
    EXPECT_NE(text.find("lights[1] sun: 2049 W/m^2, "), std::string::npos) << text;
}

// The Cornell box lit by its lamp drawn as an emissive quad (a material's `emission`) instead
// of a quad light: info gives it the same power and its light the same arrivals (the emitter's
// earliest is the nearest of 64 sampled points, so a little later, never earlier).
TEST(SceneInfo, EmissiveQuadOfASceneFileHasPowerAndArrivals) {
    ScratchDir dir;
    auto arrivals = [](const std::string& text, double& first, double& last) {
        const size_t a = text.find("arrives from ");
        const size_t b = text.find("everything it lights by ");
        if (a == std::string::npos || b == std::string::npos) return false;
        first = std::stod(text.substr(a + 13));
        last = std::stod(text.substr(b + 24));
        return true;
    };
    std::string lamp_text, emitter_text;
    info_warnings(dir, sample("cornell_box.json"), &lamp_text);
    nlohmann::json s = box();
    const nlohmann::json lamp = s["lights"][0];
    s["materials"]["lamp"] = {{"type", "diffuse"}, {"albedo", {0, 0, 0}}, {"emission", lamp["radiance"]}};
    s["shapes"].push_back({{"type", "quad"}, {"corner", lamp["corner"]}, {"edge1", lamp["edge1"]},
                           {"edge2", lamp["edge2"]}, {"material", "lamp"}});
    s.erase("lights");
    info_warnings(dir, write_scene(dir, "emitter.json", s), &emitter_text);
    const double watts = M_PI * (17 + 12 + 4) / 3.0 * 0.5 * 0.4;
    char expected[80];
    std::snprintf(expected, sizeof expected, "emissive surfaces of shapes[7] (quad): %.4g W", watts);
    EXPECT_NE(emitter_text.find(expected), std::string::npos) << expected << "\n" << emitter_text;
    double lamp_first = 0, lamp_last = 0, first = 0, last = 0;
    ASSERT_TRUE(arrivals(lamp_text, lamp_first, lamp_last)) << lamp_text;
    ASSERT_TRUE(arrivals(emitter_text, first, last)) << emitter_text;
    EXPECT_GE(first, lamp_first - 0.005);
    EXPECT_LT(first, lamp_first + 0.2);  // a grid cell of the 0.5 m x 0.4 m lamp is 6 cm (0.2 ns)
    EXPECT_NEAR(last, lamp_last, 0.2);
}

TEST(SceneWarnings, LampsAndEmissiveSurfacesInDifferentUnits) {
    ScratchDir dir;
    // Consistent: a pi W panel and a point light of pi W (0.25 W/sr = 170.75 cd).
    const std::string good = write_lamp_and_panel(dir, "good.glb", 0.25 * 683);
    EXPECT_TRUE(scale_warnings(info_warnings_with(dir, {good})).empty());
    // Written in W/sr (Blender's "Unitless" mode) and read as candela: 683 times too weak.
    const std::string unitless = write_lamp_and_panel(dir, "unitless.glb", 0.25);
    std::vector<std::string> w = scale_warnings(info_warnings_with(dir, {unitless}));
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find(unitless), std::string::npos) << w[0];
    EXPECT_NE(w[0].find("683 times less"), std::string::npos) << w[0];
    EXPECT_NE(w[0].find("--gltf-light-units radiometric"), std::string::npos) << w[0];
    EXPECT_TRUE(scale_warnings(info_warnings_with(dir, {unitless, "--gltf-light-units", "radiometric"})).empty());
    // The consistent file read as radiometric: 683 times too strong.
    w = scale_warnings(info_warnings_with(dir, {good, "--gltf-light-units", "radiometric"}));
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("683 times more"), std::string::npos) << w[0];
    EXPECT_NE(w[0].find("--gltf-light-units photometric"), std::string::npos) << w[0];
    // In a scene file the advice is the gltf shape's key.
    nlohmann::json scene = box();
    scene["shapes"].push_back({{"type", "gltf"}, {"file", unitless}});
    w = scale_warnings(info_warnings(dir, write_scene(dir, "with_model.json", scene)));
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("\"light_units\": \"radiometric\""), std::string::npos) << w[0];
    scene["shapes"].back()["light_units"] = "radiometric";
    EXPECT_TRUE(scale_warnings(info_warnings(dir, write_scene(dir, "with_model.json", scene))).empty());
}

// A scene's warnings name its file; a long path (here 600 characters) still gives lines of at
// most 300 characters, cut with a note of their length, never lines of any length.
TEST(SceneWarnings, LinesStayWithinThreeHundredCharactersWhateverTheFileName) {
    ScratchDir dir;
    nlohmann::json s = box();
    s["time"]["end_ns"] = 1.0;
    s["time"]["frames"] = 4;
    std::string folder = dir.file("");
    for (int i = 0; i < 4; ++i) {
        folder += std::string(150, 'd') + "/";
        std::filesystem::create_directory(folder);
    }
    const std::string scene = write_scene(dir, folder.substr(dir.file("").size()) + "early.json", s);
    ASSERT_GT(scene.size(), 600u);
    std::vector<std::string> w = info_warnings(dir, scene);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0].size(), 300u) << w[0];
    EXPECT_NE(w[0].find("characters in all)"), std::string::npos) << w[0];
}
