#include "core/mesh_loader.h"

#include <tiny_obj_loader.h>

#include <cmath>
#include <filesystem>

#include "config/input_file.h"
#include "foundation/errors.h"
#include "core/placement.h"

namespace sl {
namespace {

void add_quad(TriangleSoup& s, Vec3 c, Vec3 e1, Vec3 e2) {
    auto base = static_cast<uint32_t>(s.vertices.size());
    s.vertices.insert(s.vertices.end(), {c, c + e1, c + e1 + e2, c + e2});
    s.indices.insert(s.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

}  // namespace

TriangleSoup load_obj_mesh(const ShapeDesc& shape, const std::string& scene_source) {
    auto fail = [&](const std::string& why) {
        return InputError(scene_source + ": mesh '" + shape.file + "': " + why);
    };
    check_input_file(shape.file, UINT64_MAX, scene_source + ": mesh '" + shape.file + "'", "mesh file");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(shape.file, ec)) throw fail("not a readable file");
    // Parsing holds the text's numbers several times over: refuse what could exhaust memory.
    constexpr uintmax_t kMaxObjBytes = uintmax_t(1) << 30;
    uintmax_t size = std::filesystem::file_size(shape.file, ec);
    if (ec) throw fail("not a readable file");
    if (size == 0) throw fail("is empty");
    if (size > kMaxObjBytes)
        throw fail("is " + std::to_string(size >> 20) + " MiB; loading it would need about " +
                   std::to_string(3 * (size >> 20)) + " MiB, and meshes are limited to 1024 MiB of OBJ text");
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(shape.file, config)) {
        std::string msg = reader.Error();
        while (!msg.empty() && (msg.back() == '\n' || msg.back() == '\r')) msg.pop_back();
        for (char& ch : msg) if (ch == '\n') ch = ' ';
        throw fail(msg.empty() ? "cannot be parsed as OBJ" : msg);
    }
    const auto& pos = reader.GetAttrib().vertices;
    size_t nverts = pos.size() / 3;
    TriangleSoup soup;
    soup.vertices.reserve(nverts);
    for (size_t i = 0; i < nverts; ++i) {
        Vec3 p{pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]};
        if (!is_finite(p)) throw fail("vertex " + std::to_string(i + 1) + " is not finite");
        soup.vertices.push_back(rotate_xyz(p * shape.scale, shape.rotate_deg) + shape.translate);
    }
    for (const auto& sh : reader.GetShapes()) {
        for (size_t f = 0; f + 2 < sh.mesh.indices.size(); f += 3) {
            uint32_t idx[3];
            for (int k = 0; k < 3; ++k) {
                int vi = sh.mesh.indices[f + k].vertex_index;
                if (vi < 0 || static_cast<size_t>(vi) >= nverts)
                    throw fail("face index out of range" + (sh.name.empty() ? std::string() : " in object '" + sh.name + "'"));
                idx[k] = static_cast<uint32_t>(vi);
            }
            Vec3 a = soup.vertices[idx[0]], b = soup.vertices[idx[1]], c = soup.vertices[idx[2]];
            if (length(cross(b - a, c - a)) == 0) continue;  // degenerate: no area, no light
            soup.indices.insert(soup.indices.end(), {idx[0], idx[1], idx[2]});
        }
    }
    if (soup.indices.empty()) throw fail("has no triangles with area");
    return soup;
}

TriangleSoup triangulate_shape(const ShapeDesc& shape, const std::string& scene_source) {
    TriangleSoup s;
    switch (shape.type) {
    case ShapeType::Quad: add_quad(s, shape.corner, shape.edge1, shape.edge2); break;
    case ShapeType::Box: {
        Vec3 a = shape.min, d = shape.max - shape.min;
        Vec3 ex{d.x, 0, 0}, ey{0, d.y, 0}, ez{0, 0, d.z};
        add_quad(s, a, ey, ex);            // z = min
        add_quad(s, a + ez, ex, ey);       // z = max
        add_quad(s, a, ez, ey);            // x = min
        add_quad(s, a + ex, ey, ez);       // x = max
        add_quad(s, a, ex, ez);            // y = min
        add_quad(s, a + ey, ez, ex);       // y = max
        break;
    }
    case ShapeType::Mesh: return load_obj_mesh(shape, scene_source);
    case ShapeType::Sphere:
    case ShapeType::Gltf: break;  // imported by core/import, never triangulated here
    }
    return s;
}

}  // namespace sl
