#pragma once
// One GGX surface on a camera or photon path (core/bsdf/bsdf.h): the BSDF at the hit (its base
// colour times its texture), the local shading frame it is evaluated in, and a sampled bounce
// with the same bookkeeping as a specular one (core/specular_path.h): new origin, direction,
// and the inside flag and index when a rough refraction enters or leaves a solid, so that each
// leg's time stays its length times the index over c.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/bsdf/bsdf.h"
#include "core/material_table.h"
#include "core/pass_sequences.h"
#include "core/rng.h"
#include "core/scene_geometry.h"
#include "core/surface_material.h"

namespace sl {

// An orthonormal frame with +z along n: world <-> the BSDF's local frame.
struct LocalFrame {
    Vec3 t, b, n;
    explicit LocalFrame(Vec3 normal) : n(normal) { make_basis(n, t, b); }
    Vec3 local(Vec3 v) const { return {dot(v, t), dot(v, b), dot(v, n)}; }
    Vec3 world(Vec3 v) const { return t * v.x + b * v.y + n * v.z; }
};

// The one place a GGX material's per-hit parameters are made: base colour times its texture;
// glTF's metallic-roughness texture (linear) scales the roughness by G and metallic by B.
inline bsdf::Bsdf bsdf_at(const SurfaceMaterial& m, const SurfaceHit& hit) {
    bsdf::Bsdf b = m.bsdf;
    if (m.albedo_texture) b.base = b.base * m.albedo_texture->sample(hit.tex_u, hit.tex_v);
    if (m.metallic_roughness_texture) {
        const Vec3 t = m.metallic_roughness_texture->sample(hit.tex_u, hit.tex_v);
        b.alpha = bsdf::alpha_of_roughness(std::clamp(m.roughness * t.y, 0.0f, 1.0f));
        b.metallic = std::clamp(b.metallic * t.z, 0.0f, 1.0f);
    }
    return b;
}

// How camera paths and photons treat the surface at this hit (core/material_table.h): the
// material's choice, or with a metallic-roughness texture the choice its values at the hit make
// (a texture's metal half is followed as an untextured smooth metal is, its plastic half gathers).
inline GlossyUse glossy_use_at(const SurfaceMaterial& m, const bsdf::Bsdf& b) {
    if (!m.metallic_roughness_texture) return m.glossy;
    const float roughness = std::sqrt(b.alpha);  // alpha = roughness^2 above the floor kMinAlpha
    return metallic_roughness_use(b.metallic, roughness, b.transmission);
}

// Whether the BSDF has an inside (rough glass, transmissive metallic-roughness): its frame's +z
// is then the outside, known from the path's inside flag as for smooth glass.
inline bool has_inside(const bsdf::Bsdf& b) { return !bsdf::two_sided(b); }

// A metallic-roughness surface (no transmission) whose dielectric coat is smooth enough to be
// followed, over a diffuse base that gathers (camera_pass.cpp): the roughness below which metals
// are followed (kFollowBelowRoughness), some base and some coat.
inline bool smooth_coat(const bsdf::Bsdf& b) {
    return b.kind == bsdf::Kind::MetallicRoughness && b.transmission <= 0 && b.metallic < 1 &&
           std::sqrt(b.alpha) < kFollowBelowRoughness && bsdf::dielectric_scale(b) > 0 && max_component(b.base) > 0;
}

// The frame's +z: the shading normal (normal-mapped) on the side the path arrives from (d: its
// direction), or on the outside for a BSDF with an inside.
inline Vec3 frame_normal(const SurfaceMaterial& m, const bsdf::Bsdf& b, const SurfaceHit& hit, Vec3 d, bool inside) {
    const Vec3 ns = shading_normal_facing(m, hit, d);
    return has_inside(b) && inside ? -ns : ns;
}

// The three uniform numbers a BSDF sample takes: uc picks the lobe, (u1, u2) the direction in it.
struct BsdfDraw {
    float uc, u1, u2;
};

// Samples the BSDF for a path arriving along d (radiance for camera paths, importance for
// photons) and moves the path on. Returns the throughput weight f |cos| / pdf; zero when the
// draw is lost (GGX's single-scattering loss) or would leave through the wrong side of the true
// (geometric) surface, and the path ends. b: bsdf_at(m, hit), made once by the caller.
// u: the draw's numbers (uniform in [0, 1)^3). pdf (when given): the solid-angle density of the
// drawn direction.
inline Vec3 follow_glossy(const SurfaceMaterial& m, const bsdf::Bsdf& b, const SurfaceHit& hit, Vec3& o, Vec3& d,
                          bool& inside, float& inside_ior, BsdfDraw u, bsdf::Transport mode, float* pdf = nullptr) {
    const LocalFrame frame(frame_normal(m, b, hit, d, inside));
    const Vec3 wo = frame.local(-d);
    const bsdf::Sample s = bsdf::sample(b, wo, u.uc, u.u1, u.u2, mode);
    if (!s.valid) return Vec3(0);
    const Vec3 wi = normalize(frame.world(s.wi));
    const bool crossed = s.wi.z * wo.z < 0;
    const Vec3 nf = dot(d, hit.normal) < 0 ? hit.normal : -hit.normal;  // faces the arriving path
    if ((dot(wi, nf) > 0) == crossed) return Vec3(0);  // the shading normal sent it through the true surface
    if (crossed) {
        inside = !inside;
        inside_ior = m.ior;
    }
    const Vec3 side = dot(wi, hit.normal) > 0 ? hit.normal : -hit.normal;
    o = hit.position + side * ray_epsilon(hit.position, hit.t);
    d = wi;
    if (pdf) *pdf = s.pdf;
    return s.weight;
}

// The same with the numbers drawn from rng.
inline Vec3 follow_glossy(const SurfaceMaterial& m, const bsdf::Bsdf& b, const SurfaceHit& hit, Vec3& o, Vec3& d,
                          bool& inside, float& inside_ior, Rng& rng, bsdf::Transport mode, float* pdf = nullptr) {
    const float uc = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    return follow_glossy(m, b, hit, o, d, inside, inside_ior, BsdfDraw{uc, u1, u2}, mode, pdf);
}

// The k-th of n draws that together cover [0, 1)^3 evenly (a path split in n, one draw a
// branch): the 3-D Hammersley set (k/n, base-2 and base-3 radical inverses of k) shifted modulo
// 1 by one random offset. Each draw is uniform on its own (the offset is), so every branch's
// estimate keeps its mean; together they leave no lobe or part of a lobe out by chance.
inline BsdfDraw stratified_draw(int k, int n, BsdfDraw offset) {
    const uint32_t i = static_cast<uint32_t>(k);
    return {add_mod1(offset.uc, static_cast<float>(k) / static_cast<float>(n)),
            add_mod1(offset.u1, radical_inverse(i, 2)), add_mod1(offset.u2, radical_inverse(i, 3))};
}

// The same n draws for a branch's next glossy vertex: the set again, its branches shuffled by
// k -> (a k + c) mod n (a odd, n a power of two: a bijection; else k + c) and shifted by an
// offset of their own. Each branch's two draws are then independent and uniform (the second
// offset is), while over the n branches the second vertex's lobe choice and direction are
// stratified as well: of 32 branches through a glass cube, those that reflect at its far face
// are no longer a Poisson count.
struct BranchShuffle {
    uint32_t a = 1, c = 0;
};
inline BsdfDraw shuffled_draw(int k, int n, BranchShuffle s, BsdfDraw offset) {
    const uint32_t un = static_cast<uint32_t>(n), uk = static_cast<uint32_t>(k);
    const bool power_of_two = (un & (un - 1)) == 0;
    const uint32_t j = power_of_two ? (s.a * uk + s.c) & (un - 1) : (uk + s.c) % un;
    return stratified_draw(static_cast<int>(j), n, offset);
}

}  // namespace sl
