#pragma once
// Triangles of an OBJ file, transformed into the scene (scale, rotate X→Y→Z, translate).
#include <cstdint>
#include <string>
#include <vector>

#include "config/scene_desc.h"

namespace sl {

struct TriangleSoup {
    std::vector<Vec3> vertices;
    std::vector<uint32_t> indices;  // 3 per triangle
};

// Throws InputError naming the file for an unreadable or malformed mesh, or one whose
// indices are out of range. Degenerate (zero-area) triangles are dropped.
TriangleSoup load_obj_mesh(const ShapeDesc& shape, const std::string& scene_source);

// Quads, boxes and meshes as triangles (spheres are not triangulated).
TriangleSoup triangulate_shape(const ShapeDesc& shape, const std::string& scene_source);

}  // namespace sl
