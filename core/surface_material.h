#pragma once
// What a material gives at one hit: its albedo and emission, times its textures at the hit's
// texture coordinates. Camera paths, photon bounces and direct light all read these.
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

}  // namespace sl
