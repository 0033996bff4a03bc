#pragma once
// Triangles read from a mesh file (OBJ, glTF), in scene space: flat arrays a hit indexes by
// primitive, so that shading reads a normal, a UV and a material without any indirection.
#include <cstdint>
#include <vector>

#include "foundation/vec3.h"

namespace sl {

struct MeshData {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;     // per vertex (unit), or empty: flat shading
    std::vector<float> uvs;        // 2 per vertex (glTF convention: v = 0 at the image's top), or empty
    std::vector<float> tangents;   // 4 per vertex: glTF's TANGENT (xyz, handedness w), or empty
    std::vector<uint32_t> indices;  // 3 per triangle, counter-clockwise seen from the front
    std::vector<int32_t> tri_material;  // per triangle: index into SceneDesc::materials
    bool tangent_frames = false;  // a material of it draws a normal map: its hits carry a tangent

    size_t triangle_count() const { return indices.size() / 3; }
    uint64_t bytes() const {
        return positions.capacity() * sizeof(Vec3) + normals.capacity() * sizeof(Vec3) +
               (uvs.capacity() + tangents.capacity()) * sizeof(float) + indices.capacity() * 4 + tri_material.capacity() * 4;
    }
};

}  // namespace sl
