// Zero-area lights and shapes are rejected by the scene parser with a message that names the
// key; degenerate triangles in an OBJ are dropped (and a mesh of nothing but degenerate
// triangles is rejected); a scene with degenerate triangles renders without NaN or Inf.
#include <fstream>

#include "foundation/errors.h"
#include "core/import/resolve_imports.h"
#include "core/scene_geometry.h"
#include "hard_helpers.h"

namespace sl::hard {
namespace {

std::string scene_with(const std::string& shapes, const std::string& lights) {
    return R"({"camera": {"position": [0, 1, 3], "look_at": [0, 1, 0], "width": 16, "height": 16},
      "materials": {"white": {"type": "diffuse", "albedo": [0.7, 0.7, 0.7]}},
      "shapes": [)" + shapes + R"(],
      "lights": [)" + lights + R"(],
      "time": {"start_ns": 0, "end_ns": 12, "frames": 4},
      "render": {"passes": 3, "photons_per_pass": 2000, "max_depth": 4}})";
}
const std::string kFloor = R"({"type": "quad", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2], "material": "white"})";
const std::string kPoint = R"({"type": "point", "position": [0, 1.5, 0], "power": [10, 10, 10]})";

// Parses and expects InputError whose message contains every one of `parts`.
void expect_rejected(const std::string& text, std::initializer_list<const char*> parts, const std::string& base = "") {
    try {
        parse_scene_text(text, "scene.json", base);
        ADD_FAILURE() << "accepted:\n" << text;
    } catch (const InputError& e) {
        std::string msg = e.what();
        EXPECT_EQ(msg.rfind("scene.json", 0), 0u) << msg;  // names the file first
        for (const char* p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
    }
}

TEST(ZeroArea, QuadLightsAreRejected) {
    // Parallel edges, a zero edge, and edges too nearly parallel to span an area.
    expect_rejected(scene_with(kFloor, R"({"type": "quad", "corner": [0, 1.9, 0], "edge1": [1, 0, 0],
                                          "edge2": [2, 0, 0], "radiance": [1, 1, 1]})"),
                    {"lights[0].edge2", "zero area"});
    expect_rejected(scene_with(kFloor, R"({"type": "quad", "corner": [0, 1.9, 0], "edge1": [0, 0, 0],
                                          "edge2": [0, 0, 1], "radiance": [1, 1, 1]})"),
                    {"lights[0].edge2", "zero area"});
    expect_rejected(scene_with(kFloor, kPoint + R"(, {"type": "quad", "corner": [0, 1.9, 0], "edge1": [1, 0, 0],
                                          "edge2": [1, 1e-9, 0], "radiance": [1, 1, 1]})"),
                    {"lights[1].edge2", "zero area"});
}

TEST(ZeroArea, ShapesAreRejected) {
    expect_rejected(scene_with(R"({"type": "quad", "corner": [0, 0, 0], "edge1": [1, 1, 1], "edge2": [-2, -2, -2],
                                   "material": "white"})", kPoint),
                    {"shapes[0].edge2", "zero area"});
    expect_rejected(scene_with(R"({"type": "box", "min": [0, 0, 0], "max": [1, 0, 1], "material": "white"})", kPoint),
                    {"shapes[0].max"});
    expect_rejected(scene_with(R"({"type": "sphere", "center": [0, 0, 0], "radius": 0, "material": "white"})", kPoint),
                    {"shapes[0].radius"});
}

TEST(ZeroArea, LightsWithoutPowerAreRejectedWhenNoneEmits) {
    expect_rejected(scene_with(kFloor, R"({"type": "point", "position": [0, 1, 0], "power": [0, 0, 0]})"),
                    {"lights", "zero power"});
}

TEST(DegenerateTriangles, AreDroppedAndTheRestRenders) {
    TempDir dir;
    {
        std::ofstream obj(dir.file("mixed.obj"));
        obj << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nv 0 0 0\n"
               "f 1 2 3\n"   // a real triangle
               "f 1 2 4\n"   // collinear
               "f 1 1 3\n"   // a repeated vertex
               "f 1 5 2\n";  // two vertices at the same place
    }
    {
        std::ofstream obj(dir.file("flat.obj"));
        obj << "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 1\n";
    }
    auto mesh = [](const char* file) {
        return std::string(R"({"type": "mesh", "file": ")") + file + R"(", "translate": [-0.5, 0.2, 0], "material": "white"})";
    };
    SceneDesc s = parse_scene_text(scene_with(kFloor + ", " + mesh("mixed.obj"), kPoint), "scene.json", dir.path());
    SceneGeometry g(with_imports(s));  // the OBJ read as a render reads it (core/import)
    EXPECT_EQ(g.triangle_count(), 2u /* floor */ + 1u /* the one real triangle */);
    Rendered r = render(s);
    EXPECT_EQ(r.buffer_non_finite, 0u);
    EXPECT_EQ(r.image_non_finite(), 0u);
    EXPECT_GT(mean(r.steady), 0.0);

    // A mesh of nothing but degenerate triangles has nothing to show: an input error that
    // names the mesh.
    try {
        SceneDesc bad = parse_scene_text(scene_with(kFloor + ", " + mesh("flat.obj"), kPoint), "scene.json", dir.path());
        SceneGeometry gb(with_imports(bad));
        ADD_FAILURE() << "a mesh without area was accepted";
    } catch (const InputError& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find("flat.obj"), std::string::npos) << msg;
        EXPECT_NE(msg.find("no triangles with area"), std::string::npos) << msg;
    }
}

}  // namespace
}  // namespace sl::hard
