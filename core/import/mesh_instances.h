#pragma once
// A mesh placed more than once (a glTF mesh under several nodes, or one file under several
// scene entries) is held once, in its own space, with one transform per placement: Embree
// builds it once and places it by instances (core/scene_geometry.cpp), so 2,000 copies cost
// one copy plus 2,000 transforms. A mesh placed once is baked into scene space instead.
#include <cmath>
#include <memory>
#include <vector>

#include "core/import/mesh_data.h"
#include "foundation/vec3.h"

namespace sl {

// p -> L p + t, rows of [L | t] (as Embree's RTC_FORMAT_FLOAT3X4_ROW_MAJOR).
struct Affine {
    float m[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};

    Vec3 vector(Vec3 v) const {
        return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[4] * v.x + m[5] * v.y + m[6] * v.z,
                m[8] * v.x + m[9] * v.y + m[10] * v.z};
    }
    Vec3 point(Vec3 p) const { return vector(p) + Vec3(m[3], m[7], m[11]); }
    double det() const {
        return double(m[0]) * (double(m[5]) * m[10] - double(m[6]) * m[9]) -
               double(m[1]) * (double(m[4]) * m[10] - double(m[6]) * m[8]) +
               double(m[2]) * (double(m[4]) * m[9] - double(m[5]) * m[8]);
    }
    // `this` after `inner`: p -> this(inner(p)).
    Affine after(const Affine& inner) const {
        Affine r;
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 4; ++j) {
                double s = j == 3 ? m[4 * i + 3] : 0.0;
                for (int k = 0; k < 3; ++k) s += double(m[4 * i + k]) * inner.m[4 * k + j];
                r.m[4 * i + j] = static_cast<float>(s);
            }
        }
        return r;
    }
    bool finite() const {
        for (float x : m)
            if (!std::isfinite(x)) return false;
        return true;
    }
};

// Normals through an Affine: the inverse transpose of L, so that a surface's normal stays
// perpendicular to it under non-uniform scale, and its front stays its front when L mirrors
// (negative determinant). Rows, 3 x 3; not normalised.
struct NormalMatrix {
    float n[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    NormalMatrix() = default;
    explicit NormalMatrix(const Affine& a) {
        const double d = a.det();
        if (!(d != 0) || !std::isfinite(d)) return;
        auto at = [&](int r, int c) { return double(a.m[4 * r + c]); };
        // inverse transpose = cofactor matrix / det
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
                n[3 * i + j] = static_cast<float>((at(i1, j1) * at(i2, j2) - at(i1, j2) * at(i2, j1)) / d);
            }
    }
    Vec3 operator()(Vec3 v) const {
        return {n[0] * v.x + n[1] * v.y + n[2] * v.z, n[3] * v.x + n[4] * v.y + n[5] * v.z,
                n[6] * v.x + n[7] * v.y + n[8] * v.z};
    }
};

struct InstancedMesh {
    std::shared_ptr<const MeshData> mesh;  // in its own space; tri_material: scene materials
    std::vector<Affine> placements;        // into scene space, one per copy
};

// A shape's meshes placed by instances (ShapeDesc::instances). Two scene entries naming the
// same file share the InstancedMesh::mesh pointer: it is counted and built once.
struct InstancedMeshes {
    std::vector<InstancedMesh> meshes;
};

// Triangle t of `m` placed by `a`, counter-clockwise from its front: a mirroring placement
// reverses the corners' order (the second and third swap) so that the front stays outward.
// `order` receives the corner indices used, for per-vertex data.
inline void placed_triangle(const MeshData& m, size_t t, const Affine& a, Vec3 out[3], uint32_t order[3]) {
    const uint32_t* idx = &m.indices[3 * t];
    const bool mirror = a.det() < 0;
    order[0] = idx[0];
    order[1] = idx[mirror ? 2 : 1];
    order[2] = idx[mirror ? 1 : 2];
    for (int k = 0; k < 3; ++k) out[k] = a.point(m.positions[order[k]]);
}

}  // namespace sl
