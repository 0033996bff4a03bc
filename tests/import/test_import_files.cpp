// The files a model names: read only from the model's folder, only when they are regular files
// (a FIFO would block the import, /dev/zero read forever), and every number that places or
// frames the model checked; what is repeated or long in the messages is said once and short.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "tests/common/temp_dir.h"
#include "tests/import/model_writers.h"
#include "tests/pipeline/run_program.h"

namespace sl::test {
namespace {

namespace fs = std::filesystem;

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

nlohmann::json read_json_file(const std::string& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

// A valid emissive quad as model.gltf + model.bin in `dir`; returns its JSON.
nlohmann::json lamp_gltf(const TempDir& dir) {
    ModelMesh m;
    m.quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
    write_gltf(dir.file("model.gltf"), m, {{"lamp", Vec3(0), Vec3(1)}}, false);
    return read_json_file(dir.file("model.gltf"));
}

// `slowlight info FILE`: exit status 2 and one error line that holds every one of `words`.
void expect_one_error(const std::string& file, const std::vector<std::string>& words) {
    ProgramResult r = run_program({"info", file}, "", 30);
    EXPECT_FALSE(r.timed_out) << "the import blocked";
    EXPECT_EQ(r.exit_code, 2) << r.err;
    auto lines = r.error_lines();
    ASSERT_EQ(lines.size(), 1u) << r.err;
    for (const std::string& w : words) EXPECT_NE(lines[0].find(w), std::string::npos) << "no '" << w << "' in " << lines[0];
}

TEST(ImportFiles, GltfBufferOrImageThatIsNoRegularFileIsNamedForWhatItIs) {
    TempDir dir;
    nlohmann::json j = lamp_gltf(dir);
    ASSERT_EQ(::mkfifo(dir.file("fifo.bin").c_str(), 0644), 0);
    j["buffers"][0]["uri"] = "fifo.bin";
    write_text(dir.file("fifo.gltf"), j.dump());
    expect_one_error(dir.file("fifo.gltf"), {"fifo.gltf", "fifo.bin", "FIFO"});

    fs::create_directories(dir.file("folder.bin"));
    j["buffers"][0]["uri"] = "folder.bin";
    write_text(dir.file("dir.gltf"), j.dump());
    expect_one_error(dir.file("dir.gltf"), {"folder.bin", "directory"});

    // An image: the lamp's emission textured from a FIFO.
    j = lamp_gltf(dir);
    ASSERT_EQ(::mkfifo(dir.file("fifo.png").c_str(), 0644), 0);
    j["images"] = {{{"uri", "fifo.png"}}};
    j["textures"] = {{{"source", 0}}};
    j["materials"][0]["emissiveTexture"] = {{"index", 0}};
    write_text(dir.file("image.gltf"), j.dump());
    expect_one_error(dir.file("image.gltf"), {"fifo.png", "FIFO"});
}

// tinygltf looks in the working directory when a file is not beside the model, and an absolute
// URI would name any file on the machine: both are looked for in the model's folder only.
TEST(ImportFiles, GltfFilesAreLookedForInTheModelsFolderOnly) {
    TempDir dir;
    fs::create_directories(dir.file("models"));
    fs::create_directories(dir.file("work"));
    lamp_gltf(dir);  // model.gltf + model.bin at the top
    nlohmann::json j = read_json_file(dir.file("model.gltf"));
    fs::copy_file(dir.file("model.bin"), dir.file("work/only_here.bin"));
    j["buffers"][0]["uri"] = "only_here.bin";
    write_text(dir.file("models/cwd.gltf"), j.dump());
    j["buffers"][0]["uri"] = dir.file("model.bin");  // absolute, and the file exists
    write_text(dir.file("models/abs.gltf"), j.dump());
    j["buffers"][0]["uri"] = "../model.bin";  // a shared folder: allowed
    write_text(dir.file("models/up.gltf"), j.dump());

    const fs::path before = fs::current_path();
    fs::current_path(dir.file("work"));  // where only_here.bin is
    ProgramResult cwd = run_program({"info", dir.file("models/cwd.gltf")});
    ProgramResult abs = run_program({"info", dir.file("models/abs.gltf")});
    ProgramResult up = run_program({"info", dir.file("models/up.gltf")});
    fs::current_path(before);

    EXPECT_EQ(cwd.exit_code, 2) << cwd.err;
    ASSERT_EQ(cwd.error_lines().size(), 1u) << cwd.err;
    EXPECT_NE(cwd.error_lines()[0].find("only_here.bin: not found"), std::string::npos) << cwd.err;
    EXPECT_EQ(abs.exit_code, 2) << abs.err;
    ASSERT_EQ(abs.error_lines().size(), 1u) << abs.err;
    EXPECT_NE(abs.error_lines()[0].find("not found"), std::string::npos) << abs.err;
    EXPECT_EQ(up.exit_code, 0) << up.err;
}

TEST(ImportFiles, ObjLibrariesAndTexturesThatAreNoRegularFiles) {
    TempDir dir;
    const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    ASSERT_EQ(::mkfifo(dir.file("fifo.mtl").c_str(), 0644), 0);
    write_text(dir.file("fifo.obj"), "mtllib fifo.mtl\n" + quad);
    expect_one_error(dir.file("fifo.obj"), {"fifo.mtl", "FIFO"});

    fs::create_directories(dir.file("wood.png"));
    write_text(dir.file("tex.mtl"), "newmtl lamp\nKe 1 1 1\nnewmtl wood\nmap_Kd wood.png\n");
    write_text(dir.file("tex.obj"), "mtllib tex.mtl\nusemtl lamp\n" + quad + "usemtl wood\nf 1 2 3\n");
    expect_one_error(dir.file("tex.obj"), {"tex.mtl:4", "wood.png", "directory"});
}

TEST(ImportFiles, NodeAndCameraNumbersMustMakeSense) {
    TempDir dir;
    const nlohmann::json ok = lamp_gltf(dir);
    auto rejected = [&](nlohmann::json j, const std::vector<std::string>& words) {
        write_text(dir.file("bad.gltf"), j.dump());
        fs::copy_file(dir.file("model.bin"), dir.file("bad.bin"), fs::copy_options::overwrite_existing);
        j["buffers"][0]["uri"] = "bad.bin";
        write_text(dir.file("bad.gltf"), j.dump());
        std::vector<std::string> all = words;
        all.push_back("bad.gltf");
        expect_one_error(dir.file("bad.gltf"), all);
    };
    auto j = ok;
    j["nodes"][0]["rotation"] = {0, 0, 0, 0};
    rejected(j, {"node 0", "zero quaternion"});
    j = ok;
    j["nodes"][0]["translation"] = {0, 1e300, 0};
    rejected(j, {"node 0", "translation"});
    j = ok;
    j["nodes"][0]["scale"] = {1, 1, 1e12};
    rejected(j, {"node 0", "scale"});

    // A camera on a second node.
    j = ok;
    j["nodes"][0]["children"] = {1};
    j["nodes"].push_back({{"camera", 0}, {"translation", {0.5, 0.5, 3}}});
    j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}, {"aspectRatio", 1.5}}}}};
    auto with_camera = j;
    {
        write_text(dir.file("cam.gltf"), with_camera.dump());
        ProgramResult r = run_program({"info", dir.file("cam.gltf")});
        EXPECT_EQ(r.exit_code, 0) << r.err;
    }
    j = with_camera;
    j["cameras"][0]["perspective"]["yfov"] = 1e-9;
    rejected(j, {"camera 0", "yfov"});
    j = with_camera;
    j["cameras"][0]["perspective"]["aspectRatio"] = 1e12;  // once a 1 x 256 video
    rejected(j, {"camera 0", "aspectRatio"});
    j = with_camera;
    j["cameras"][0]["perspective"]["aspectRatio"] = -2;
    rejected(j, {"camera 0", "aspectRatio"});
}

// Every line of stderr, and how many there are.
std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> out;
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        out.push_back(text.substr(start, end - start));
        start = end + 1;
    }
    return out;
}

TEST(ImportFiles, RepeatedWarningsOnceWithACountAndNoLineLongerThan300) {
    TempDir dir;
    nlohmann::json j = lamp_gltf(dir);
    // 2,000 spots whose inner cone is wider than the outer: the same warning 2,000 times.
    nlohmann::json lights = nlohmann::json::array();
    for (int i = 0; i < 2000; ++i)
        lights.push_back({{"type", "spot"}, {"intensity", 1.0}, {"spot", {{"innerConeAngle", 0.6}, {"outerConeAngle", 0.3}}}});
    j["extensionsUsed"] = {"KHR_lights_punctual"};
    j["extensions"]["KHR_lights_punctual"]["lights"] = lights;
    for (int i = 0; i < 2000; ++i)
        j["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", i}}}}}, {"translation", {0.5, 0.5, 1.0}}});
    j["nodes"][0]["children"] = nlohmann::json::array();
    for (int i = 0; i < 2000; ++i) j["nodes"][0]["children"].push_back(i + 1);
    // A light whose name is 100,000 characters: the warning that names it stays short.
    j["extensions"]["KHR_lights_punctual"]["lights"].push_back(
        {{"type", "point"}, {"intensity", 1.0}, {"range", 5.0}, {"name", std::string(100000, 'x')}});
    j["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 2000}}}}}, {"translation", {0.5, 0.5, 1.0}}});
    j["nodes"][0]["children"].push_back(2001);
    write_text(dir.file("many.gltf"), j.dump());
    ProgramResult r = run_program({"info", dir.file("many.gltf")}, "", 60);
    ASSERT_EQ(r.exit_code, 0) << r.err.substr(0, 2000);
    size_t spot_lines = 0, long_name_lines = 0;
    for (const std::string& l : lines_of(r.err)) {
        EXPECT_LE(l.size(), 300u) << l.substr(0, 400);
        if (l.find("wider than its outer cone") != std::string::npos) {
            ++spot_lines;
            EXPECT_NE(l.find("(2000 times)"), std::string::npos) << l;
        }
        if (l.find("xxxxxxxxxx") != std::string::npos) ++long_name_lines;
    }
    EXPECT_EQ(spot_lines, 1u) << r.err.substr(0, 3000);
    EXPECT_EQ(long_name_lines, 1u) << "the range warning of the light with the long name";
}

}  // namespace
}  // namespace sl::test
