// A glTF node graph is bounded by what it places, not by its depth: a graph whose paths double
// at each level is refused at once with the count, a cycle is named, and a mesh reused by
// several nodes is held once and placed once per node.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "core/import/imported_file.h"
#include "foundation/errors.h"
#include "tests/common/temp_dir.h"
#include "tests/import/model_writers.h"

namespace sl::test {
namespace {

using nlohmann::json;

// A .gltf of one lamp-lit quad (two triangles), whose node list `rewrite` then replaces.
std::string graph_file(TempDir& dir, const std::function<void(json&)>& rewrite) {
    ModelMesh m;
    m.quad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0);
    write_gltf(dir.file("g.gltf"), m, {{"lamp", Vec3(0), Vec3(1)}}, /*binary=*/false);
    json j;
    std::ifstream(dir.file("g.gltf")) >> j;
    rewrite(j);
    std::ofstream(dir.file("g.gltf")) << j.dump();
    return dir.file("g.gltf");
}

std::string error_of(const std::string& file) {
    try {
        read_gltf(file, true);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// Node i has node i + 1 twice among its children: 2^levels paths to the last node.
void doubling_chain(json& j, int levels, bool mesh_at_the_end) {
    j["nodes"] = json::array();
    for (int i = 0; i < levels; ++i) j["nodes"].push_back({{"children", {i + 1, i + 1}}});
    j["nodes"].push_back(mesh_at_the_end ? json{{"mesh", 0}} : json::object());
    j["scenes"] = json::array({{{"nodes", {0}}}});
}

// Node k of the chain is placed 2^k times: 2^(levels + 1) - 1 placements in all.
TEST(GltfNodeGraph, PathsThatDoubleAtEachLevelAreRefusedWithTheNodesTheyWouldPlace) {
    TempDir dir;
    // 2^40 placements of the mesh: before the count, a walk that never ended.
    const std::string m = error_of(graph_file(dir, [](json& j) { doubling_chain(j, 40, true); }));
    EXPECT_NE(m.find("its node graph places " + std::to_string((uint64_t(1) << 41) - 1) + " nodes"), std::string::npos) << m;
    EXPECT_NE(m.find("at most 16777216 are rendered"), std::string::npos) << m;
}

TEST(GltfNodeGraph, EmptyNodesThatDoubleAreBoundedToo) {
    TempDir dir;
    const std::string m = error_of(graph_file(dir, [](json& j) {
        doubling_chain(j, 60, false);
        j["nodes"].push_back({{"mesh", 0}});
        j["scenes"][0]["nodes"].push_back(j["nodes"].size() - 1);
    }));
    // 2^61 - 1 placements of the chain, and the mesh's own root.
    EXPECT_NE(m.find("its node graph places " + std::to_string(uint64_t(1) << 61) + " nodes"), std::string::npos) << m;
}

TEST(GltfNodeGraph, TrianglesAreCountedAgainstTheirOwnBound) {
    TempDir dir;
    // 2^23 placements (within the node bound) of an index accessor that claims 2^25 corners.
    const std::string m = error_of(graph_file(dir, [](json& j) {
        doubling_chain(j, 22, true);
        // The primitive's indices, and a view that claims room for them (neither is read: the
        // count refuses the file first; a count beyond its view is left to the accessor's check).
        j["accessors"][3]["count"] = 1u << 25;
        j["bufferViews"][j["accessors"][3]["bufferView"].get<size_t>()]["byteLength"] = 1u << 27;
    }));
    EXPECT_NE(m.find("its node graph places " + std::to_string((uint64_t(1) << 22) * ((1u << 25) / 3)) + " triangles"),
              std::string::npos) << m;
}

TEST(GltfNodeGraph, ACycleIsNamed) {
    TempDir dir;
    const std::string m = error_of(graph_file(dir, [](json& j) {
        j["nodes"] = json::array({{{"mesh", 0}, {"children", {1}}}, {{"children", {2}}}, {{"children", {1}}}});
        j["scenes"] = json::array({{{"nodes", {0}}}});
    }));
    EXPECT_NE(m.find("node 1 is its own ancestor (a cycle)"), std::string::npos) << m;
}

// Held once, in its own space, with the three placements (the nested one multiplied out).
TEST(GltfNodeGraph, AMeshReusedByThreeNodesIsPlacedThreeTimes) {
    TempDir dir;
    const std::string file = graph_file(dir, [](json& j) {
        j["nodes"] = json::array({{{"mesh", 0}},
                                  {{"mesh", 0}, {"translation", {0, 1, 0}}},
                                  {{"children", {0, 1}}, {"translation", {5, 0, 0}}}});
        j["nodes"][0]["translation"] = {0, 2, 0};
        j["scenes"] = json::array({{{"nodes", {2, 0}}}});  // node 0 twice: under 2 and as a root
    });
    const ImportedFile f = read_gltf(file, true);
    EXPECT_EQ(f.mesh.triangle_count(), 0u);
    ASSERT_EQ(f.instanced.size(), 1u);
    ASSERT_EQ(f.instanced[0].mesh.triangle_count(), 2u);
    ASSERT_EQ(f.instanced[0].placements.size(), 3u);
    const Vec3 origins[3] = {{5, 2, 0}, {5, 1, 0}, {0, 2, 0}};  // node 0 under 2, node 1 under 2, node 0
    for (int k = 0; k < 3; ++k) {
        const Vec3 o = f.instanced[0].placements[static_cast<size_t>(k)].point(Vec3(0));
        EXPECT_FLOAT_EQ(o.x, origins[k].x);
        EXPECT_FLOAT_EQ(o.y, origins[k].y);
        EXPECT_FLOAT_EQ(o.z, origins[k].z);
    }
}

}  // namespace
}  // namespace sl::test
