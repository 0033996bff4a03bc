#pragma once
// What a material gives at one hit: its albedo and emission, times its textures at the hit's
// texture coordinates, and its shading normal with its normal map applied. Camera paths,
// photon bounces and direct light all read these.
#include <cmath>

#include "core/material_table.h"
#include "core/scene_geometry.h"
#include "core/texture.h"

namespace sl {

inline Vec3 albedo_at(const SurfaceMaterial& m, const SurfaceHit& hit) {
    if (!m.albedo_texture) return m.albedo;
    return m.albedo * m.albedo_texture->sample(hit.tex_u, hit.tex_v);
}

// Radiance leaving an emissive surface towards a viewer arriving along d (zero from the back
// of a one-sided emitter).
inline Vec3 emission_at(const SurfaceMaterial& m, const SurfaceHit& hit, Vec3 d) {
    if (!m.emits() || (!m.double_sided && dot(d, hit.front) >= 0)) return Vec3(0);
    if (!m.emission_texture) return m.emission;
    return m.emission * m.emission_texture->sample(hit.tex_u, hit.tex_v);
}

// How far (a cosine) a normal-mapped shading normal is kept above the true surface, and towards
// the path that arrives at it.
inline constexpr float kMinMappedCos = 0.01f;

// The shading normal with the material's normal map applied, on the geometric normal's side:
// glTF's tangent space (+x the tangent, +y the bitangent, +z the interpolated normal; texel c
// -> 2c - 1, x and y times the scale), the tangent made orthogonal to the normal. The
// interpolated normal when there is no map or no tangent frame.
inline Vec3 mapped_normal(const SurfaceMaterial& m, const SurfaceHit& hit) {
    const Vec3 n = hit.shading_normal;
    if (!m.normal_texture || hit.tangent_sign == 0) return n;
    const Vec3 c = m.normal_texture->sample(hit.tex_u, hit.tex_v) * 2.0f - Vec3(1);
    Vec3 t = hit.tangent - n * dot(n, hit.tangent);
    const float lt = length(t);
    if (!(lt > 1e-6f)) return n;
    t = t / lt;
    const Vec3 b = cross(n, t) * hit.tangent_sign;
    Vec3 p = t * (c.x * m.normal_scale) + b * (c.y * m.normal_scale) + n * c.z;
    const float lp = length(p);
    if (!(lp > 0) || !std::isfinite(lp)) return n;
    p = p / lp;
    // A map that tips the normal below the true surface: lifted back above it.
    const float g = dot(p, hit.normal);
    if (g < kMinMappedCos) p = normalize(p + hit.normal * (kMinMappedCos - g));
    return p;
}

// The shading normal on the side of a path arriving along d (camera or photon). With a normal
// map, also turned towards the path when the map tilts it away (the path would see the back of
// its shading hemisphere: the black fringes of normal maps), just enough that -d is
// kMinMappedCos above it. Without a map: the interpolated normal, as it always was.
inline Vec3 shading_normal_facing(const SurfaceMaterial& m, const SurfaceHit& hit, Vec3 d) {
    const bool toward = dot(d, hit.normal) < 0;
    if (!m.normal_texture) return toward ? hit.shading_normal : -hit.shading_normal;
    Vec3 n = mapped_normal(m, hit);
    if (!toward) n = -n;
    const float c = -dot(d, n);
    if (c < kMinMappedCos) n = normalize(n - d * (kMinMappedCos - c));
    return n;
}

}  // namespace sl
