#pragma once
// Reads every mesh and glTF file a scene names and merges what they bring into the scene:
// triangles (placed by the entry's scale, rotation and translation), materials (unless the
// entry names one, which then covers the whole file), the textures those materials use
// (decoded now, and only those), lights, and the list of files read. Prints one `warning:`
// line per approximation. Throws InputError naming the file for anything malformed, and when
// the scene then has no light at all.
#include <cstdint>
#include <optional>
#include <string>

#include "config/scene_desc.h"

namespace sl {

// What the imported files may hold at most once decoded. Their meshes are parsed first and the
// textures' headers read; past the bound nothing is decoded and the error says what it needs.
struct ImportBudget {
    uint64_t bytes = 0;  // 0: the machine's physical memory
    std::string what;    // names the bound in the message: "--max-memory 2G"
};

void resolve_imports(SceneDesc& scene, const ImportBudget& budget = {});

// A resolved copy (the scene itself when it is resolved already).
SceneDesc with_imports(const SceneDesc& scene);

// The first camera of the first glTF file the scene imports, placed like its triangles.
std::optional<CameraDesc> imported_camera(const SceneDesc& scene);

// Geometry held by imported meshes and their textures (bytes), for `info` and the memory plan:
// a mesh placed by instances counts once, plus its transforms.
uint64_t imported_mesh_bytes(const SceneDesc& scene);
uint64_t texture_bytes(const SceneDesc& scene);
// Embree's own copy of the vertices and indices and its BVH (measured, see docs/scenes.md).
uint64_t imported_bvh_bytes(const SceneDesc& scene);
// Triangles as placed (a mesh placed N times counts N times), and as held (once).
size_t imported_triangles(const SceneDesc& scene);
size_t held_triangles(const SceneDesc& scene);
size_t emissive_triangles(const SceneDesc& scene);  // as placed
// Placements of meshes held once and placed by instances (core/import/mesh_instances.h).
size_t imported_instances(const SceneDesc& scene);

}  // namespace sl
