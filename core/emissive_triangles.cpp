#include "core/emissive_triangles.h"

#include <algorithm>
#include <cmath>

#include "core/import/mesh_data.h"
#include "core/import/mesh_instances.h"
#include "core/sampling.h"
#include "core/shape_triangles.h"
#include "core/texture.h"

namespace sl {

// A triangle of material m sends this much power per m^2 (W/m^2): its radiance (times its
// emission texture's mean) times pi, from one face or both.
Vec3 EmissiveTriangles::power_per_area(const MaterialDesc& m) const {
    const Vec3 mean = m.emission_texture >= 0
                          ? m.emission * scene_->textures[static_cast<size_t>(m.emission_texture)].image->mean
                          : m.emission;
    return mean * (kPi * (m.double_sided ? 2.0f : 1.0f));
}

float EmissiveTriangles::pdf_area_of(const MaterialDesc& m) const {
    if (!(total_weight_ > 0)) return 0;
    const float w = average(power_per_area(m));
    return w > 0 ? static_cast<float>(w / total_weight_) : 0.0f;
}

EmissiveTriangles::EmissiveTriangles(const SceneDesc& scene) : scene_(&scene) {
    std::vector<double> weight;
    // One triangle of an emissive material; uv: its corners' texture coordinates, or null.
    auto add = [&](Vec3 a, Vec3 b, Vec3 c, const MaterialDesc& mat, const float* uv[3]) {
        Triangle tri;
        tri.v0 = a;
        tri.e1 = b - a;
        tri.e2 = c - a;
        Vec3 n = cross(tri.e1, tri.e2);
        float len = length(n);
        if (!(len > 0) || !std::isfinite(len)) return;
        tri.normal = n / len;
        tri.area = 0.5f * len;
        tri.radiance = mat.emission;
        tri.texture = mat.emission_texture;
        tri.two_sided = mat.double_sided;
        for (int k = 0; k < 3; ++k) {
            tri.uv[2 * k] = uv ? uv[k][0] : 0;
            tri.uv[2 * k + 1] = uv ? uv[k][1] : 0;
        }
        Vec3 p = power_per_area(mat) * tri.area;
        if (!(average(p) > 0)) return;
        power_ += p;
        weight.push_back(average(p));
        tris_.push_back(tri);
    };
    // A mesh's emissive triangles; a mesh placed by instances: its emissive triangles, and only
    // those, in scene space, one per copy (a mirroring copy keeps its front:
    // core/import/mesh_instances.h).
    auto add_mesh = [&](const MeshData& m, const Affine* placed) {
        for (size_t t = 0; t < m.triangle_count(); ++t) {
            const MaterialDesc& mat = scene.materials[static_cast<size_t>(m.tri_material[t])];
            if (!mat.emits()) continue;
            uint32_t idx[3];
            Vec3 v[3];
            if (placed) {
                placed_triangle(m, t, *placed, v, idx);
            } else {
                for (int k = 0; k < 3; ++k) {
                    idx[k] = m.indices[3 * t + k];
                    v[k] = m.positions[idx[k]];
                }
            }
            const float* uv[3] = {nullptr, nullptr, nullptr};
            if (!m.uvs.empty())
                for (int k = 0; k < 3; ++k) uv[k] = &m.uvs[2 * idx[k]];
            add(v[0], v[1], v[2], mat, m.uvs.empty() ? nullptr : uv);
        }
    };
    for (const ShapeDesc& s : scene.shapes) {
        if (s.mesh) add_mesh(*s.mesh, nullptr);
        if (s.instances)
            for (const InstancedMesh& im : s.instances->meshes)
                for (const Affine& a : im.placements) add_mesh(*im.mesh, &a);
        if (!s.mesh && !s.instances) {
            // A scene file's quad or box of an emissive material (a sphere cannot emit: the
            // parser refuses it).
            if (s.type == ShapeType::Sphere || s.material < 0 ||
                !scene.materials[static_cast<size_t>(s.material)].emits())
                continue;
            const TriangleSoup soup = triangulate_shape(s);
            for (size_t t = 0; t + 2 < soup.indices.size(); t += 3)
                add(soup.vertices[soup.indices[t]], soup.vertices[soup.indices[t + 1]],
                    soup.vertices[soup.indices[t + 2]], scene.materials[static_cast<size_t>(s.material)], nullptr);
        }
    }
    double total = 0;
    for (double w : weight) total += w;
    total_weight_ = total;
    double run = 0;
    for (double w : weight) {
        run += w;
        cdf_.push_back(static_cast<float>(run / total));
        prob_.push_back(static_cast<float>(w / total));
    }
    if (!cdf_.empty()) cdf_.back() = 1;
}

uint64_t EmissiveTriangles::bytes_per_triangle() { return sizeof(Triangle) + 2 * sizeof(float) + sizeof(double); }

EmitterPoint EmissiveTriangles::sample(float u1, float u2) const {
    size_t i = static_cast<size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u1) - cdf_.begin());
    i = std::min(i, tris_.size() - 1);
    const Triangle& t = tris_[i];
    const float lo = i > 0 ? cdf_[i - 1] : 0.0f;
    const float ur = std::clamp((u1 - lo) / std::max(prob_[i], 1e-30f), 0.0f, 1.0f);
    // Uniform on the triangle: b1 = 1 - sqrt(ur), b2 = u2 sqrt(ur).
    const float su = std::sqrt(ur), b1 = 1 - su, b2 = u2 * su;
    EmitterPoint e;
    e.position = t.v0 + t.e1 * b1 + t.e2 * b2;
    e.normal = t.normal;
    e.two_sided = t.two_sided;
    e.radiance = t.radiance;
    if (t.texture >= 0) {
        float u = t.uv[0] + (t.uv[2] - t.uv[0]) * b1 + (t.uv[4] - t.uv[0]) * b2;
        float v = t.uv[1] + (t.uv[3] - t.uv[1]) * b1 + (t.uv[5] - t.uv[1]) * b2;
        e.radiance = e.radiance * scene_->textures[static_cast<size_t>(t.texture)].image->sample(u, v);
    }
    e.pdf_area = prob_[i] / t.area;
    return e;
}

}  // namespace sl
