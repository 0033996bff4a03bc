// OBJ faces are read as distinct corners (v/vt/vn): a mesh holds each distinct vertex once,
// a face written again is drawn once (with one counted warning), and an ordinary file still
// gives exactly its triangles, its vertices in the order its faces first use them.
#include <gtest/gtest.h>

#include <fstream>

#include "core/import/imported_file.h"
#include "core/import/resolve_imports.h"
#include "tests/common/temp_dir.h"
#include "tests/import/model_writers.h"

namespace sl::test {
namespace {

TEST(ObjCorners, SevenMillionRepeatedFacesCostOneTriangle) {
    TempDir dir;
    {
        std::ofstream o(dir.file("corners.obj"));
        o << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
        const std::string chunk = [] {
            std::string c;
            for (int i = 0; i < 100000; ++i) c += "f 1 2 3\n";
            return c;
        }();
        for (int i = 0; i < 70; ++i) o << chunk;  // 7,000,000 faces, 56 MB
    }
    SceneDesc s;
    s.source = "<corners>";
    LightDesc l;
    l.power = Vec3(1);
    l.position = {0, 0, 1};
    s.lights.push_back(l);
    MaterialDesc grey;
    s.materials.push_back(grey);
    ShapeDesc sh;
    sh.type = ShapeType::Mesh;
    sh.file = dir.file("corners.obj");
    sh.material = 0;
    s.shapes.push_back(sh);
    const ImportedFile f = read_obj_mtl(dir.file("corners.obj"), false);
    EXPECT_EQ(f.mesh.triangle_count(), 1u);
    EXPECT_EQ(f.mesh.positions.size(), 3u);
    ASSERT_EQ(f.warnings.size(), 1u);
    EXPECT_NE(f.warnings[0].find("6999999 faces repeat an earlier face"), std::string::npos) << f.warnings[0];
    resolve_imports(s);
    // What the memory plan adds up for it: one triangle's arrays and BVH.
    EXPECT_LT(imported_mesh_bytes(s) + imported_bvh_bytes(s), 1024u);
}

TEST(ObjCorners, AnOrdinaryFileGivesExactlyItsTrianglesInOrder) {
    TempDir dir;
    ModelMesh m;
    for (int i = 0; i < 5; ++i) m.quad({0.1f * i, 0, 0}, {0.1f, 0, 0.01f * i}, {0, 0.3f, 0}, i % 2);
    m.box({1, 1, 1}, {1.5f, 2, 1.25f}, 1);
    write_obj(dir.file("m.obj"), "m.mtl", m, {{"a", Vec3(0.5f)}, {"b", Vec3(0.2f)}});
    const ImportedFile f = read_obj_mtl(dir.file("m.obj"), true);
    EXPECT_TRUE(f.warnings.empty());
    // Each corner i/i/i is vertex i of the model, first used in that order.
    ASSERT_EQ(f.mesh.positions.size(), m.positions.size());
    for (size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_EQ(f.mesh.positions[i].x, m.positions[i].x);
        EXPECT_EQ(f.mesh.positions[i].y, m.positions[i].y);
        EXPECT_EQ(f.mesh.positions[i].z, m.positions[i].z);
        EXPECT_NEAR(f.mesh.uvs[2 * i], m.uvs[2 * i], 1e-7f);
    }
    EXPECT_EQ(f.mesh.indices, m.indices);
    EXPECT_EQ(f.mesh.tri_material, (std::vector<int32_t>(m.tri_material.begin(), m.tri_material.end())));
}

TEST(ObjCorners, OnlyTheSameFaceWithTheSameFrontAndMaterialIsARepeat) {
    TempDir dir;
    std::ofstream(dir.file("r.mtl")) << "newmtl a\nKd 0.5 0.5 0.5\nnewmtl b\nKd 0.2 0.2 0.2\n";
    std::ofstream(dir.file("r.obj")) << "mtllib r.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n"
                                        "usemtl a\nf 1 2 3\nf 2 3 1\nf 3//1 1//1 2//1\n"  // a rotation repeats; other corners do not
                                        "f 1 3 2\n"          // the other front: a face of its own
                                        "usemtl b\nf 1 2 3\n";  // another material: a face of its own
    const ImportedFile f = read_obj_mtl(dir.file("r.obj"), true);
    EXPECT_EQ(f.mesh.triangle_count(), 4u);
    ASSERT_EQ(f.warnings.size(), 1u);
    EXPECT_NE(f.warnings[0].find(": 1 faces repeat an earlier face"), std::string::npos) << f.warnings[0];
}

}  // namespace
}  // namespace sl::test
