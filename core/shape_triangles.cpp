#include "core/shape_triangles.h"

#include <stdexcept>

namespace sl {
namespace {

void add_quad(TriangleSoup& s, Vec3 c, Vec3 e1, Vec3 e2) {
    auto base = static_cast<uint32_t>(s.vertices.size());
    s.vertices.insert(s.vertices.end(), {c, c + e1, c + e1 + e2, c + e2});
    s.indices.insert(s.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

}  // namespace

TriangleSoup triangulate_shape(const ShapeDesc& shape) {
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
    case ShapeType::Sphere: break;  // intersected as a sphere, never triangulated
    case ShapeType::Mesh:
    case ShapeType::Gltf:  // read by core/import/resolve_imports into the shape's mesh first
        throw std::logic_error("triangulate_shape: shape '" + shape.file + "' was not imported");
    }
    return s;
}

}  // namespace sl
