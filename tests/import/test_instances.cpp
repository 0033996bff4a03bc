// Meshes placed more than once are held once and placed by Embree instances: what they cost
// (one copy plus transforms, in the bytes the memory plan adds up), what they render (the same
// image as the same copies written out one by one), the power of an emissive copy, and the
// front of a mirrored copy. (core/import/mesh_instances.h)
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/emissive_triangles.h"
#include "core/import/mesh_instances.h"
#include "core/import/resolve_imports.h"
#include "core/scene_geometry.h"
#include "config/run_options.h"
#include "pipeline/memory_plan.h"
#include "stages/output/png_io.h"
#include "tests/common/temp_dir.h"
#include "tests/import/model_writers.h"
#include "tests/render/render_helpers.h"
#include "tests/render/scenes_for_tests.h"

namespace sl::test {
namespace {

using nlohmann::json;

// A grid of n x n quads (2 n^2 triangles) in the x-z plane, facing up.
ModelMesh grid(int n, int material) {
    ModelMesh m;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            m.quad({i / float(n) - 0.5f, 0, (j + 1) / float(n) - 0.5f}, {1.0f / n, 0, 0}, {0, 0, -1.0f / n}, material);
    return m;
}

// Rewrites a file write_gltf made (one mesh, under node 0): `nodes` place it; with `separate`,
// every node gets a mesh of its own (the same primitives), so that nothing is placed twice.
void place_by_nodes(const std::string& file, const json& nodes, bool separate) {
    json j;
    std::ifstream(file) >> j;
    const json lights = j["nodes"].size() > 1 ? j["nodes"][1] : json();
    j["nodes"] = json::array();
    j["scenes"][0]["nodes"] = json::array();
    const json mesh = j["meshes"][0];
    j["meshes"] = json::array();
    for (const json& n : nodes) {
        json node = n;
        if (separate || j["meshes"].empty()) j["meshes"].push_back(mesh);
        node["mesh"] = j["meshes"].size() - 1;
        j["nodes"].push_back(node);
        j["scenes"][0]["nodes"].push_back(j["nodes"].size() - 1);
    }
    if (!lights.is_null()) {
        j["nodes"].push_back(lights);
        j["scenes"][0]["nodes"].push_back(j["nodes"].size() - 1);
    }
    std::ofstream(file) << j.dump();
}

SceneDesc lit_scene_with(ShapeType type, const std::vector<std::string>& files) {
    SceneDesc s;
    s.source = "<instances>";
    LightDesc l;
    l.position = {0, 5, 0};
    l.power = Vec3(10);
    s.lights.push_back(l);
    for (const std::string& f : files) s.shapes.push_back(model_shape(f, type));
    return s;
}

uint64_t plan_bytes(const SceneDesc& s) { return imported_mesh_bytes(s) + imported_bvh_bytes(s); }

TEST(Instances, TwoThousandCopiesCostOneCopyPlusTransforms) {
    TempDir dir;
    write_gltf(dir.file("one.gltf"), grid(40, 0), {{"grey", Vec3(0.5f)}}, false);  // 3,200 triangles
    write_gltf(dir.file("many.gltf"), grid(40, 0), {{"grey", Vec3(0.5f)}}, false);
    json nodes = json::array();
    for (int k = 0; k < 2000; ++k) nodes.push_back({{"translation", {1.5 * (k % 50), 0.0, 1.5 * (k / 50)}}});
    place_by_nodes(dir.file("many.gltf"), nodes, false);
    SceneDesc one = lit_scene_with(ShapeType::Gltf, {dir.file("one.gltf")});
    SceneDesc many = lit_scene_with(ShapeType::Gltf, {dir.file("many.gltf")});
    resolve_imports(one);
    resolve_imports(many);
    EXPECT_EQ(imported_triangles(many), 2000u * imported_triangles(one));
    EXPECT_EQ(held_triangles(many), imported_triangles(one));
    EXPECT_EQ(imported_instances(many), 2000u);
    const uint64_t copy = plan_bytes(one), all = plan_bytes(many);
    std::printf("one copy %llu bytes, 2,000 copies %llu bytes\n", (unsigned long long)copy, (unsigned long long)all);
    // One copy, plus each placement's transform and instance budget: a 200th of 2,000 copies.
    EXPECT_EQ(all, copy + 2000 * (sizeof(Affine) + 1024));
    EXPECT_LT(all, 2000 * copy / 200);
    // Embree sees every copy: the BVH reports the placed triangles.
    SceneGeometry g(many);
    EXPECT_EQ(g.triangle_count(), imported_triangles(many));
    EXPECT_NEAR(g.bounds_max().x, 1.5f * 49 + 0.5f, 1e-4f);
    EXPECT_NEAR(g.bounds_max().z, 1.5f * 39 + 0.5f, 1e-4f);
}

TEST(Instances, OneFileNamedByManyEntriesIsHeldOnce) {
    TempDir dir;
    write_obj(dir.file("grid.obj"), "grid.mtl", grid(20, 0), {{"grey", Vec3(0.5f)}});
    SceneDesc one = lit_scene_with(ShapeType::Mesh, {dir.file("grid.obj")});
    SceneDesc many = lit_scene_with(ShapeType::Mesh, std::vector<std::string>(300, dir.file("grid.obj")));
    for (size_t i = 0; i < many.shapes.size(); ++i) many.shapes[i].translate = {1.5f * static_cast<float>(i), 0, 0};
    resolve_imports(one);
    resolve_imports(many);
    EXPECT_EQ(imported_triangles(many), 300u * imported_triangles(one));
    EXPECT_EQ(imported_instances(many), 300u);
    EXPECT_EQ(plan_bytes(many), plan_bytes(one) + 300 * (sizeof(Affine) + 1024));
    EXPECT_EQ(many.materials.size(), one.materials.size());  // the file's materials once too
    SceneGeometry g(many);
    // A ray down onto copy 7 hits it in the scene's space, facing up.
    SurfaceHit h;
    ASSERT_TRUE(g.intersect({1.5f * 7 + 0.1f, 1, 0.05f}, {0, -1, 0}, 0, 10, h));
    EXPECT_NEAR(h.t, 1.0f, 1e-5f);
    EXPECT_NEAR(h.front.y, 1.0f, 1e-6f);
    EXPECT_FALSE(g.intersect({1.5f * 300 + 0.1f, 1, 0.05f}, {0, -1, 0}, 0, 10, h));
}

// Two boxes and a rotated, non-uniformly scaled, mirrored third in the Cornell box: once as one
// mesh under three nodes (instances), once as three meshes (baked into the scene): the same image.
void expect_instanced_renders_as_written_out(const ModelMaterial& material, const std::string& image) {
    TempDir dir;
    if (!image.empty()) {  // a constant tilted normal map, (0.30, 0.40, 0.87) in tangent space
        std::vector<uint8_t> px;
        for (int i = 0; i < 16; ++i) px.insert(px.end(), {166, 179, 238});
        write_png(dir.file(image), 4, 4, px.data());
    }
    ModelMesh box;
    box.box({-0.2f, 0, -0.2f}, {0.2f, 0.5f, 0.2f}, 0);
    const json nodes = json::array(
        {{{"translation", {-0.4, 0.0, -0.3}}},
         {{"translation", {0.4, 0.0, 0.2}}, {"rotation", {0.0, 0.3826834, 0.0, 0.9238795}}, {"scale", {1.0, 1.6, 0.7}}},
         {{"translation", {0.0, 1.2, -0.5}}, {"scale", {-0.8, 0.5, 1.2}}}});  // mirrored: det < 0
    for (const char* name : {"instanced", "separate"}) {
        const std::string f = dir.file(std::string(name) + ".gltf");
        write_gltf(f, box, {material}, false);
        place_by_nodes(f, nodes, std::string(name) == "separate");
    }
    auto scene = [&](const std::string& file, uint64_t seed) {
        SceneDesc s = small_box(24, 8, 20000);
        s.render.seed = seed;
        s.shapes.erase(std::remove_if(s.shapes.begin(), s.shapes.end(),
                                      [](const ShapeDesc& sh) { return sh.type == ShapeType::Box; }),
                       s.shapes.end());
        s.shapes.push_back(model_shape(file, ShapeType::Gltf));
        return s;
    };
    const SceneDesc inst = with_imports(scene(dir.file("instanced.gltf"), 1));
    ASSERT_EQ(imported_instances(inst), 3u);
    ASSERT_EQ(imported_instances(with_imports(scene(dir.file("separate.gltf"), 1))), 0u);
    const Rendered a = render_all(scene(dir.file("instanced.gltf"), 1));
    const Rendered b = render_all(scene(dir.file("separate.gltf"), 1));
    const Rendered b2 = render_all(scene(dir.file("separate.gltf"), 2));
    const double spread = rmse(b.steady, b2.steady), d = rmse(a.steady, b.steady);
    std::printf("seed-to-seed %.4g, instanced vs written out %.4g; means %.5g / %.5g\n", spread, d, mean(a.steady),
                mean(b.steady));
    ASSERT_GT(spread, 0);
    // The same triangles, the same seed: only rounding differs (a transform in Embree, not in
    // the vertices), far below the noise (measured: 1.5e-8 against 0.24).
    EXPECT_LT(d, 0.01 * spread);
    EXPECT_NEAR(mean(a.steady), mean(b.steady), 0.002 * mean(b.steady));
}

TEST(Instances, InstancedCopiesRenderAsTheSameCopiesWrittenOut) {
    expect_instanced_renders_as_written_out({"white", Vec3(0.73f)}, "");
}

// A normal map on copies: the tangent frame is made in the mesh's own space and placed with the
// copy (rotated, scaled, mirrored), as it is when the copies are written out.
TEST(Instances, NormalMappedCopiesRenderAsTheSameCopiesWrittenOut) {
    ModelMaterial white("white", Vec3(0.73f));
    white.normal_image = "tilt.png";
    expect_instanced_renders_as_written_out(white, "tilt.png");
}

// An emissive panel (0.5 x 0.4 m, L = 10 W sr^-1 m^-2, one-sided) under three nodes, one of
// them scaled 2 x 3 in its plane, one mirrored: power = pi L (A + 6 A + A).
TEST(Instances, AnEmissiveMeshPlacedThreeTimesIsThreeEmittersOfTheRightPower) {
    TempDir dir;
    ModelMesh panel;
    panel.quad({0, 0, 0}, {0.5f, 0, 0}, {0, 0, -0.4f}, 0);  // front +y
    write_gltf(dir.file("p.gltf"), panel, {{"lamp", Vec3(0), Vec3(10)}}, false);
    place_by_nodes(dir.file("p.gltf"),
                   json::array({{{"translation", {0.0, 1.0, 0.0}}},
                                {{"translation", {2.0, 1.0, 0.0}}, {"scale", {2.0, 1.0, 3.0}}},
                                {{"translation", {-2.0, 1.0, 0.0}}, {"scale", {-1.0, 1.0, 1.0}}}}),
                   false);
    SceneDesc s = lit_scene_with(ShapeType::Gltf, {dir.file("p.gltf")});
    s.lights.clear();
    resolve_imports(s);
    ASSERT_EQ(imported_instances(s), 3u);
    EXPECT_EQ(emissive_triangles(s), 6u);
    const EmissiveTriangles e(s);
    const double expected = kPiDouble * 10 * 0.5 * 0.4 * (1 + 6 + 1);
    EXPECT_EQ(e.size(), 6u);
    EXPECT_NEAR(e.power().x, expected, 1e-5 * expected);
    // Every copy, the mirrored one too, shines down its front (+y), as the panel does.
    for (int i = 0; i < 64; ++i) {
        const EmitterPoint p = e.sample((i + 0.5f) / 64, 0.37f);
        EXPECT_NEAR(p.normal.y, 1.0f, 1e-6f);
        EXPECT_NEAR(p.position.y, 1.0f, 1e-6f);
    }
}

// The emitters' table holds each placed emissive triangle in scene space: the memory plan counts
// them per copy (2,000 copies of a lamp panel: 4,000 entries), not once per held mesh.
TEST(Instances, EmissiveCopiesAreCountedInTheMemoryPlanPerCopy) {
    TempDir dir;
    ModelMesh panel;
    panel.quad({0, 0, 0}, {0.5f, 0, 0}, {0, 0, -0.4f}, 0);
    json nodes = json::array();
    for (int k = 0; k < 2000; ++k) nodes.push_back({{"translation", {1.0 * (k % 50), 1.0, 1.0 * (k / 50)}}});
    write_gltf(dir.file("lamps.gltf"), panel, {{"lamp", Vec3(0), Vec3(10)}}, false);
    write_gltf(dir.file("grey.gltf"), panel, {{"grey", Vec3(0.5f)}}, false);
    place_by_nodes(dir.file("lamps.gltf"), nodes, false);
    place_by_nodes(dir.file("grey.gltf"), nodes, false);
    SceneDesc lamps = lit_scene_with(ShapeType::Gltf, {dir.file("lamps.gltf")});
    SceneDesc grey = lit_scene_with(ShapeType::Gltf, {dir.file("grey.gltf")});
    resolve_imports(lamps);
    resolve_imports(grey);
    const RunOptions o;
    const uint64_t extra = memory_baseline(lamps, o).scene - memory_baseline(grey, o).scene;
    EXPECT_EQ(EmissiveTriangles(lamps).size(), 4000u);
    EXPECT_EQ(extra, 4000 * EmissiveTriangles::bytes_per_triangle());
    EXPECT_GE(EmissiveTriangles::bytes_per_triangle(), 5 * sizeof(Vec3));  // the record alone holds 5 vectors
}

// A closed box mirrored by its node: every face's front (and shading normal) still points out
// of the box, as the same box written out with its winding reversed does (glTF's rule).
TEST(Instances, AMirroredCopyKeepsItsNormalsOutward) {
    TempDir dir;
    ModelMesh box;
    box.box({-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}, 0);
    write_gltf(dir.file("b.gltf"), box, {{"white", Vec3(0.5f)}}, false);
    place_by_nodes(dir.file("b.gltf"),
                   json::array({{{"translation", {0.0, 0.0, 0.0}}, {"scale", {-1.0, 2.0, 1.0}}},
                                {{"translation", {5.0, 0.0, 0.0}}, {"scale", {1.0, -1.0, -1.0}}}}),
                   false);
    SceneDesc s = lit_scene_with(ShapeType::Gltf, {dir.file("b.gltf")});
    resolve_imports(s);
    ASSERT_EQ(imported_instances(s), 2u);
    SceneGeometry g(s);
    const Vec3 centres[2] = {{0, 0, 0}, {5, 0, 0}};
    const Vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int b = 0; b < 2; ++b)
        for (Vec3 d : dirs) {
            // From outside toward the centre (slightly off it, not through an edge).
            const Vec3 target = centres[b] + Vec3(0.11f, 0.07f, 0.05f);
            const Vec3 from = target - d * 3.0f;
            SurfaceHit h;
            ASSERT_TRUE(g.intersect(from, d, 0, 10, h));
            EXPECT_NEAR(dot(h.front, d), -1.0f, 1e-5f) << "box " << b << " ray " << d.x << d.y << d.z;
            EXPECT_NEAR(dot(h.shading_normal, h.front), 1.0f, 1e-5f);
        }
    // The clear radius sees the copies in the scene's space: from 0.2 m above the top of the
    // tall (2 m) box, the nearest surface above a plane below it is its top, 0.2 m away.
    const float r = g.clear_radius({0, 1.2f, 0}, 5, {0, -2, 0}, {0, 1, 0}, 0.5f);
    EXPECT_NEAR(r, 0.2f, 1e-5f);
}

}  // namespace
}  // namespace sl::test
