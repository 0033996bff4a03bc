#pragma once
// What the renderer relies on in any file an importer accepted: every index inside its arrays,
// every number finite. A fuzz target traps on a violation (an accepted file that would make the
// renderer read out of bounds or trace NaN).
#include <cmath>

#include "core/import/imported_file.h"

namespace sl::fuzz {

inline void check_mesh(const ImportedFile& f, const MeshData& m) {
    if (m.indices.size() % 3 != 0) __builtin_trap();
    for (uint32_t i : m.indices)
        if (i >= m.positions.size()) __builtin_trap();
    if (!m.normals.empty() && m.normals.size() != m.positions.size()) __builtin_trap();
    if (!m.uvs.empty() && m.uvs.size() != 2 * m.positions.size()) __builtin_trap();
    if (m.tri_material.size() != m.triangle_count()) __builtin_trap();
    for (int32_t t : m.tri_material)
        if (t < 0 || static_cast<size_t>(t) >= f.materials.size()) __builtin_trap();
    for (const Vec3& p : m.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) __builtin_trap();
}

// The meshes placed once and those placed by instances (with finite placements).
inline void check_imported(const ImportedFile& f) {
    check_mesh(f, f.mesh);
    for (const ImportedInstances& in : f.instanced) {
        check_mesh(f, in.mesh);
        if (in.placements.size() < 2) __builtin_trap();
        for (const Affine& a : in.placements)
            if (!a.finite()) __builtin_trap();
    }
}

}  // namespace sl::fuzz
