// Loading a large imported mesh: writes a UV sphere of about segments^2 triangles (vertex
// normals, an emissive quad above it) as .glb and as .obj, then for each reads it
// (resolve_imports) and builds the renderer's scene (RenderContext: Embree BVH, emitters),
// printing the time of each step and the resident memory each adds, per triangle.
//   ./build/bench_mesh_scale [segments = 1000]
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "foundation/constants.h"
#include "core/import/resolve_imports.h"
#include "stages/render/render_context.h"
#include "tests/common/temp_dir.h"
#include "tests/import/model_writers.h"

namespace {

double rss_bytes() {
    std::ifstream f("/proc/self/statm");
    long pages = 0, resident = 0;
    f >> pages >> resident;
    return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE));
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

sl::test::ModelMesh sphere(int segments) {
    using sl::Vec3;
    sl::test::ModelMesh m;
    const int rings = segments / 2;
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s <= segments; ++s) {
            double th = sl::kPiDouble * r / rings, ph = 2 * sl::kPiDouble * s / segments;
            Vec3 p(static_cast<float>(std::sin(th) * std::cos(ph)), static_cast<float>(std::cos(th)),
                   static_cast<float>(-std::sin(th) * std::sin(ph)));
            m.positions.push_back(p);
            m.normals.push_back(p);
            m.uvs.insert(m.uvs.end(), {0, 0});
        }
    auto at = [&](int r, int s) { return static_cast<uint32_t>(r * (segments + 1) + s); };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            if (r > 0) m.indices.insert(m.indices.end(), {at(r, s), at(r + 1, s), at(r + 1, s + 1)});
            if (r < rings - 1) m.indices.insert(m.indices.end(), {at(r, s), at(r + 1, s + 1), at(r, s + 1)});
            m.tri_material.insert(m.tri_material.end(), {0, 0});
        }
    m.tri_material.resize(m.indices.size() / 3);
    m.quad({-0.5f, 3, -0.5f}, {1, 0, 0}, {0, 0, 1}, 1);  // facing up: flip it to face the sphere
    std::swap(m.indices[m.indices.size() - 5], m.indices[m.indices.size() - 4]);
    std::swap(m.indices[m.indices.size() - 2], m.indices[m.indices.size() - 1]);
    return m;
}

}  // namespace

int main(int argc, char** argv) {
    const int segments = argc > 1 ? std::atoi(argv[1]) : 1000;
    sl::test::TempDir dir("sl_bench_mesh");
    const auto mesh = sphere(segments);
    const std::vector<sl::test::ModelMaterial> mats = {{"grey", sl::Vec3(0.7f)}, {"lamp", sl::Vec3(0), sl::Vec3(10)}};
    sl::test::write_gltf(dir.file("sphere.glb"), mesh, mats, true);
    sl::test::write_obj(dir.file("sphere.obj"), "sphere.mtl", mesh, mats);
    std::printf("%-6s %10s %10s %8s %8s %12s %12s %12s\n", "file", "triangles", "file MB", "read s", "BVH s",
                "read B/tri", "BVH B/tri", "kept B/tri");
    for (const char* name : {"sphere.glb", "sphere.obj"}) {
        sl::SceneDesc s;
        s.source = dir.file(name);
        s.camera.position = {0, 0, 4};
        s.camera.look_at = {0, 0, 0};
        s.camera.width = s.camera.height = 16;
        sl::ShapeDesc sh;
        sh.type = std::string(name).ends_with(".glb") ? sl::ShapeType::Gltf : sl::ShapeType::Mesh;
        sh.file = dir.file(name);
        sh.material = -1;
        s.shapes.push_back(sh);
        const double rss0 = rss_bytes();
        auto t0 = std::chrono::steady_clock::now();
        sl::resolve_imports(s);
        const double read_s = seconds_since(t0);
        const double rss1 = rss_bytes();
        t0 = std::chrono::steady_clock::now();
        double rss2 = 0;
        {
            sl::RenderContext ctx(s);
            rss2 = rss_bytes();
        }
        const double bvh_s = seconds_since(t0);
        const double tris = static_cast<double>(sl::imported_triangles(s));
        std::printf("%-6s %10.0f %10.1f %8.2f %8.2f %12.0f %12.0f %12.0f\n", name + 7, tris,
                    static_cast<double>(std::filesystem::file_size(sh.file)) / 1e6, read_s, bvh_s, (rss1 - rss0) / tris,
                    (rss2 - rss1) / tris, static_cast<double>(sl::imported_mesh_bytes(s)) / tris);
    }
    return 0;
}
