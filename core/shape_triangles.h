#pragma once
// The built-in flat shapes as triangles. OBJ and glTF files are read by core/import (the one
// OBJ reader is core/import/obj_mtl_reader.cpp) before the scene's geometry is built.
#include <cstdint>
#include <string>
#include <vector>

#include "config/scene_desc.h"

namespace sl {

struct TriangleSoup {
    std::vector<Vec3> vertices;
    std::vector<uint32_t> indices;  // 3 per triangle
};

// Quads and boxes as triangles (spheres are not triangulated: none). A mesh or glTF shape that
// was not imported is a logic error.
TriangleSoup triangulate_shape(const ShapeDesc& shape);

}  // namespace sl
