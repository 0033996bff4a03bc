// Runs every row of docs/bad-inputs.md through the real program: the exit status and the one
// `error:` line must be what the page says. SLOWLIGHT_UPDATE_BAD_INPUTS=1 rewrites the page.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "process.h"

namespace sl {
namespace {

namespace fs = std::filesystem;

const nlohmann::json& base_scene() {
    static const nlohmann::json base = nlohmann::json::parse(R"({
        "camera": {"position": [0, 1, 3], "look_at": [0, 1, 0], "width": 16, "height": 16},
        "materials": {"w": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
        "shapes": [{"type": "quad", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2], "material": "w"}],
        "lights": [{"type": "point", "position": [0, 1.5, 0], "power": [1, 1, 1]}],
        "time": {"start_ns": 0, "end_ns": 10, "frames": 2},
        "render": {"passes": 1, "photons_per_pass": 100}})");
    return base;
}

struct Row {
    std::string line, what, args, scene;
    int exit = 0;
    std::string err;
};

std::string unquote(const std::string& cell) {  // `text` -> text
    size_t a = cell.find('`'), b = cell.rfind('`');
    return a == std::string::npos || a == b ? "" : cell.substr(a + 1, b - a - 1);
}

std::vector<std::string> cells(const std::string& line) {
    std::vector<std::string> out;
    std::string cur;
    bool in_code = false;
    for (size_t i = 1; i < line.size(); ++i) {
        char c = line[i];
        if (c == '`') in_code = !in_code;
        if (c == '|' && !in_code) {
            out.push_back(cur);
            cur.clear();
        } else {
            cur += c;
        }
    }
    return out;
}

std::string doc_path() { return std::string(test::source_dir()) + "/docs/bad-inputs.md"; }

std::vector<Row> read_rows() {
    std::ifstream f(doc_path());
    std::vector<Row> rows;
    bool table = false;
    for (std::string line; std::getline(f, line);) {
        if (line.rfind("|---", 0) == 0) { table = true; continue; }
        if (!table || line.rfind("| ", 0) != 0) continue;
        auto c = cells(line);
        if (c.size() < 5) continue;
        Row r;
        r.line = line;
        r.what = c[0].substr(1, c[0].size() - 2);
        r.args = unquote(c[1]);
        r.scene = unquote(c[2]);
        r.exit = std::stoi(c[3]);
        r.err = unquote(c[4]);
        rows.push_back(r);
    }
    return rows;
}

void make_fixtures(const std::string& dir) {
    fs::create_directories(dir + "/fixtures/out.mp4");
    std::ofstream(dir + "/fixtures/empty.obj");
    std::ofstream garbage(dir + "/fixtures/garbage.obj", std::ios::binary);
    for (int i = 0; i < 2048; ++i) garbage.put(static_cast<char>(i * 37));
    std::ofstream(dir + "/fixtures/bad_index.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n";
    std::ofstream(dir + "/fixtures/flat.obj") << "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n";
    std::ofstream(dir + "/fixtures/huge.obj");
    fs::resize_file(dir + "/fixtures/huge.obj", uintmax_t(2) << 30);  // sparse: no disk used
    std::ofstream(dir + "/fixtures/tri.obj") << "v -1 0 -1\nv 1 0 -1\nv 0 0 1\nf 1 2 3\n";
    // Files that never end: a FIFO nobody writes to, and a link to an endless device.
    mkfifo((dir + "/fixtures/fifo.json").c_str(), 0644);
    mkfifo((dir + "/fixtures/fifo.obj").c_str(), 0644);
    fs::create_symlink("/dev/zero", dir + "/fixtures/zero.obj");
    // A folder where a frame should go: the run fails after the video has started.
    fs::create_directories(dir + "/fixtures/pngs/frame_0001.png");
    // Cubes for retime (side-car: frames 1, 1x1 pixels, unless the case says otherwise).
    auto npy = [&](const std::string& name, const std::string& shape, const std::vector<float>& values,
                   const std::string& sidecar) {
        std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': " + shape + ", }";
        dict.append((64 - (10 + dict.size() + 1) % 64) % 64, ' ');
        dict += '\n';
        std::ofstream f(dir + "/fixtures/" + name, std::ios::binary);
        f << std::string("\x93NUMPY\x01\x00", 8) << char(dict.size() & 0xff) << char(dict.size() >> 8) << dict;
        f.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
        std::ofstream(dir + "/fixtures/" + name + ".json") << sidecar;
    };
    const std::string one = R"({"start_ns": 0, "end_ns": 1, "frames": 1, "fps": 24, "width": 1, "height": 1})";
    const std::vector<float> ok(9, 0.5f);
    npy("dim_1e20.npy", "(100000000000000000000, 1, 1, 3)", ok, one);
    npy("claims_96gib.npy", "(1000, 4096, 2048, 3)", {}, one);
    std::vector<float> nan = ok;
    nan[4] = std::nanf("");
    npy("nan.npy", "(3, 1, 1, 3)", nan, one);
    std::vector<float> negative = ok;
    negative[7] = -1;
    npy("negative.npy", "(3, 1, 1, 3)", negative, one);
    npy("fps_1e9.npy", "(3, 1, 1, 3)", ok, R"({"start_ns": 0, "end_ns": 1, "frames": 1, "fps": 1e9, "width": 1, "height": 1})");
    // Hostile models (run as `info fixtures/NAME`): an OBJ whose mtllib names a file that is no
    // MTL, or a Ke of 1e38; an emissive OBJ quad whose power overflows; a glTF lamp quad (4 float
    // VEC3 positions, 6 uint indices in lamp.bin) forged in one place each.
    std::ofstream(dir + "/fixtures/secret.txt") << "root:x:0:0:SECRET:/root:/bin/bash\n";
    const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    std::ofstream(dir + "/fixtures/leak.obj") << "mtllib secret.txt\n" << quad;
    std::ofstream(dir + "/fixtures/hot.mtl") << "newmtl sun\nKd 0 0 0\nKe 1e38 1e38 1e38\n";
    std::ofstream(dir + "/fixtures/hot.obj") << "mtllib hot.mtl\nusemtl sun\n" << quad;
    std::ofstream(dir + "/fixtures/vast.mtl") << "newmtl sun\nKe 1e30 1e30 1e30\n";
    std::ofstream(dir + "/fixtures/vast.obj") << "mtllib vast.mtl\nusemtl sun\nv 0 0 0\nv 100000 0 0\n"
                                               << "v 100000 100000 0\nv 0 100000 0\nf 1 2 3 4\n";
    {
        const float pos[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
        const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
        std::ofstream bin(dir + "/fixtures/lamp.bin", std::ios::binary);
        bin.write(reinterpret_cast<const char*>(pos), sizeof pos);
        bin.write(reinterpret_cast<const char*>(idx), sizeof idx);
    }
    const nlohmann::json lamp = nlohmann::json::parse(R"({"asset": {"version": "2.0"}, "scene": 0,
        "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "materials": [{"name": "lamp", "emissiveFactor": [1, 1, 1]}],
        "buffers": [{"uri": "lamp.bin", "byteLength": 72}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 24}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                      {"bufferView": 1, "componentType": 5125, "count": 6, "type": "SCALAR"}]})");
    auto gltf = [&](const std::string& name, const std::string& patch) {
        nlohmann::json j = lamp;
        j.merge_patch(nlohmann::json::parse(patch));
        std::ofstream(dir + "/fixtures/" + name) << j.dump();
    };
    gltf("count_wraps.gltf", R"({"accessors": [{"bufferView": 0, "componentType": 5126, "count": 4611686018427387904, "type": "VEC3"},
                                              {"bufferView": 1, "componentType": 5125, "count": 6, "type": "SCALAR"}]})");
    gltf("offset_wraps.gltf", R"({"accessors": [{"bufferView": 0, "byteOffset": 18446744073709551608, "componentType": 5126, "count": 4, "type": "VEC3"},
                                               {"bufferView": 1, "componentType": 5125, "count": 6, "type": "SCALAR"}]})");
    gltf("view_wraps.gltf", R"({"bufferViews": [{"buffer": 0, "byteOffset": 16, "byteLength": 18446744073709551600},
                                               {"buffer": 0, "byteOffset": 48, "byteLength": 24}]})");
    gltf("stride_4.gltf", R"({"bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48, "byteStride": 4},
                                             {"buffer": 0, "byteOffset": 48, "byteLength": 24}]})");
    gltf("image_view.gltf", R"({"bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                                               {"buffer": 0, "byteOffset": 48, "byteLength": 24},
                                               {"buffer": 0, "byteOffset": 0, "byteLength": 100000000}],
                               "images": [{"bufferView": 2, "mimeType": "image/png"}]})");
    gltf("strength_1e38.gltf", R"({"extensionsUsed": ["KHR_materials_emissive_strength"], "materials": [{"name": "lamp",
        "emissiveFactor": [1, 1, 1], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 1e38}}}]})");
    gltf("light_1e38.gltf", R"({"extensionsUsed": ["KHR_lights_punctual"], "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0}, {"extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "name": "flash", "intensity": 1e38}]}}})");
    mkfifo((dir + "/fixtures/fifo.bin").c_str(), 0644);
    gltf("buffer_fifo.gltf", R"({"buffers": [{"uri": "fifo.bin", "byteLength": 72}]})");
    gltf("buffer_absolute.gltf", R"({"buffers": [{"uri": "/etc/passwd", "byteLength": 72}]})");
    gltf("zero_quaternion.gltf", R"({"nodes": [{"mesh": 0, "rotation": [0, 0, 0, 0]}]})");
    gltf("aspect_1e12.gltf", R"({"scenes": [{"nodes": [0, 1]}], "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 3]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1, "aspectRatio": 1e12}}]})");
    std::string deep = lamp.dump();  // dumped as text: the JSON library would recurse as deep
    deep.insert(1, "\"extras\":" + std::string(100000, '[') + std::string(100000, ']') + ",");
    std::ofstream(dir + "/fixtures/deep.gltf") << deep;
}

std::string scene_text(const std::string& cell) {
    if (cell.rfind("raw:", 0) == 0) return nlohmann::json::parse(cell.substr(4)).get<std::string>();
    nlohmann::json s = base_scene();
    if (cell.rfind("patch:", 0) == 0) s.merge_patch(nlohmann::json::parse(cell.substr(6)));
    std::string text = s.dump();
    if (cell.rfind("sub:", 0) == 0) {
        size_t arrow = cell.find("=>");
        std::string from = cell.substr(4, arrow - 4), to = cell.substr(arrow + 2);
        size_t at = text.find(from);
        if (at == std::string::npos) throw std::runtime_error("sub pattern not in the base scene: " + from);
        text.replace(at, from.size(), to);
    }
    return text;
}

std::string mask_sizes(const std::string& s) {
    static const std::regex size(R"([0-9]+(\.[0-9]+)? (B|KiB|MiB|GiB|TiB))");
    return std::regex_replace(s, size, "<size>");
}

std::vector<std::string> split_args(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    for (std::string a; in >> a;) out.push_back(a == "SCENE" ? "bad.json" : a);
    if (!out.empty() && out[0] == "render") out.push_back("--no-progress");
    return out;
}

TEST(BadInputs, EveryDocumentedCaseGetsItsOneErrorLine) {
    std::vector<Row> rows = read_rows();
    ASSERT_GE(rows.size(), 40u);
    const bool update = std::getenv("SLOWLIGHT_UPDATE_BAD_INPUTS") != nullptr;
    std::string dir = test::fresh_dir("bad_inputs");
    make_fixtures(dir);
    std::ifstream in(doc_path());
    std::stringstream doc;
    doc << in.rdbuf();
    std::string page = doc.str();
    for (Row& r : rows) {
        SCOPED_TRACE(r.what);
        fs::remove(dir + "/bad.json");
        if (r.scene != "-") std::ofstream(dir + "/bad.json", std::ios::binary) << scene_text(r.scene);
        const std::string scene_before = r.scene == "-" ? "" : test::read_text(dir + "/bad.json");
        // Run in the scratch folder so that messages name relative paths.
        std::string cwd = fs::current_path();
        fs::current_path(dir);
        test::RunResult res = test::run(split_args(r.args), dir, 120);
        fs::current_path(cwd);
        auto errors = test::error_lines(res.err);
        std::string err;
        for (auto& e : errors) err += (err.empty() ? "" : " / ") + e;
        err = std::regex_replace(err, std::regex(dir), ".");
        EXPECT_EQ(errors.size(), 1u) << res.err;
        EXPECT_TRUE(res.status == 1 || res.status == 2) << res.status;
        if (update) {
            std::string row = "| " + r.what + " | `" + r.args + "` | `" + r.scene + "` | " + std::to_string(res.status) +
                              " | `" + err + "` |";
            page.replace(page.find(r.line), r.line.size(), row);
        } else {
            EXPECT_EQ(res.status, r.exit);
            // Sizes such as the machine's memory differ between machines: compare them as "<size>".
            EXPECT_EQ(mask_sizes(err), mask_sizes(r.err));
        }
        // Nothing that looks whole is left behind, no input is clobbered, no temporary stays.
        EXPECT_FALSE(fs::exists(dir + "/out.xyz"));
        EXPECT_FALSE(fs::exists(dir + "/no"));
        for (const char* out : {"/out.mp4", "/v.mp4", "/s.json", "/c.npy"}) {
            EXPECT_FALSE(fs::exists(dir + out)) << out;
            fs::remove(dir + out);
        }
        if (r.scene != "-") {
            EXPECT_EQ(test::read_text(dir + "/bad.json"), scene_before);
        }
        for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it)
            EXPECT_NE(it->path().filename().string().rfind(".slowlight-tmp-", 0), 0u) << it->path();
        // libav's and x264's own lines never reach stderr: only our prefixed lines do.
        std::istringstream lines(res.err);
        for (std::string line; std::getline(lines, line);)
            EXPECT_TRUE(line.rfind("error:", 0) == 0 || line.rfind("warning:", 0) == 0 ||
                        line.rfind("slowlight:", 0) == 0)
                << line;
    }
    if (update) std::ofstream(doc_path()) << page;
    fs::remove_all(dir);
}

}  // namespace
}  // namespace sl
