#include "core/emissive_triangles.h"

#include <algorithm>
#include <cmath>

#include "core/import/mesh_data.h"
#include "core/sampling.h"
#include "core/shape_triangles.h"
#include "core/texture.h"

namespace sl {

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
        Vec3 mean = tri.texture >= 0 ? tri.radiance * scene.textures[static_cast<size_t>(tri.texture)].image->mean
                                     : tri.radiance;
        Vec3 p = mean * (kPi * tri.area * (tri.two_sided ? 2.0f : 1.0f));
        if (!(average(p) > 0)) return;
        power_ += p;
        weight.push_back(average(p));
        tris_.push_back(tri);
    };
    for (const ShapeDesc& s : scene.shapes) {
        if (!s.mesh) {
            // A scene file's quad or box of an emissive material (a sphere cannot emit: the
            // parser refuses it).
            if (s.type == ShapeType::Sphere || s.material < 0 ||
                !scene.materials[static_cast<size_t>(s.material)].emits())
                continue;
            const TriangleSoup soup = triangulate_shape(s);
            for (size_t t = 0; t + 2 < soup.indices.size(); t += 3)
                add(soup.vertices[soup.indices[t]], soup.vertices[soup.indices[t + 1]],
                    soup.vertices[soup.indices[t + 2]], scene.materials[static_cast<size_t>(s.material)], nullptr);
            continue;
        }
        const MeshData& m = *s.mesh;
        for (size_t t = 0; t < m.triangle_count(); ++t) {
            const MaterialDesc& mat = scene.materials[static_cast<size_t>(m.tri_material[t])];
            if (!mat.emits()) continue;
            const uint32_t* idx = &m.indices[3 * t];
            const float* uv[3] = {nullptr, nullptr, nullptr};
            if (!m.uvs.empty())
                for (int k = 0; k < 3; ++k) uv[k] = &m.uvs[2 * idx[k]];
            add(m.positions[idx[0]], m.positions[idx[1]], m.positions[idx[2]], mat, m.uvs.empty() ? nullptr : uv);
        }
    }
    double total = 0;
    for (double w : weight) total += w;
    double run = 0;
    for (double w : weight) {
        run += w;
        cdf_.push_back(static_cast<float>(run / total));
        prob_.push_back(static_cast<float>(w / total));
    }
    if (!cdf_.empty()) cdf_.back() = 1;
}

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
