#pragma once
// The glass inside Blender 3.x's Principled BSDF (Cycles 3.4, Principled v1, distribution "GGX",
// single scattering), for metallic-roughness with "principled": "blender3": what Blender 3.x users
// see, so it is drawn as Cycles draws it, not as Walter et al.'s rough dielectric. Cycles weighs
// the glass by (1 - metallic) transmission and splits it into two closures by ONE Fresnel read at
// the macro-surface, F = fresnel_dielectric(dot(wo, n_shading), eta), wo the camera side:
//   reflection  F D G2 / (4 cos_o cos_i), white (specular tint 0 makes its microfacet Fresnel 1);
//   refraction  C (1 - F) x GGX transmission, no Fresnel at the microfacet, the same alpha.
// Not reciprocal: photons (importance transport) follow the adjoint f_imp(wo, wi) = f_rad(wi, wo),
// which reads F at wi. Local frame, wo.z > 0; eta = the index across the surface from wo's side.
#include <algorithm>
#include <cmath>

#include "core/bsdf/fresnel.h"
#include "core/bsdf/ggx.h"
#include "core/bsdf/microfacet.h"
#include "foundation/vec3.h"

namespace sl::bsdf {

// Cycles' F_macro: at the camera-side direction, wo for radiance, wi for importance (wi below
// the surface reads the inside's index, as fresnel_dielectric does for a negative cosine).
inline float v1_glass_fresnel(Vec3 wo, Vec3 wi, float eta, Transport mode) {
    return fresnel_dielectric(mode == Transport::Radiance ? wo.z : wi.z, eta);
}

// f of the glass without its weight (1 - metallic) transmission; colour: the base colour C.
inline Vec3 v1_glass_eval(const Ggx& g, Vec3 wo, Vec3 wi, float eta, Vec3 colour, Transport mode) {
    const float f = v1_glass_fresnel(wo, wi, eta, mode);
    Vec3 wm;
    if (wi.z > 0) return Vec3(f * ggx_reflection(g, wo, wi, wm));
    if (!refraction_half_vector(wo, wi, eta, wm)) return Vec3(0);
    return colour * ((1 - f) * ggx_transmission(g, wo, wi, wm, eta, mode));
}

// The chance that a drawn microfacet wm reflects. Radiance: F at wo, so every draw weighs
// G2/G1 (times C / eta^2 through). Importance reads F at wi, unknown before the draw: the share
// of the two candidates' Fresnel terms, F(reflected) / (F(reflected) + 1 - F(refracted)), which
// pdf can rebuild from wm; F at wo alone never drew refraction from inside beyond the critical
// angle, where tilted microfacets still transmit.
inline float v1_glass_reflect_share(Vec3 wo, Vec3 wm, float eta, Transport mode) {
    if (mode == Transport::Radiance) return fresnel_dielectric(wo.z, eta);
    Vec3 wt;
    float etap;
    if (!refract_about(wo, wm, eta, wt, etap)) return 1;  // total internal reflection at wm
    const float fr = fresnel_dielectric(std::max(0.0f, reflect_about(wo, wm).z), eta);
    const float ft = fresnel_dielectric(wt.z, eta);
    const float sum = fr + 1 - ft;
    return sum > 0 ? fr / sum : 0.5f;
}

// The density of the glass's own draw (below): a visible normal, then reflection or refraction.
inline float v1_glass_pdf(const Ggx& g, Vec3 wo, Vec3 wi, float eta, Transport mode) {
    Vec3 wm;
    if (wi.z > 0) {
        if (ggx_reflection(g, wo, wi, wm) == 0) return 0;
        return ggx_reflection_pdf(g, wo, wm) * v1_glass_reflect_share(wo, wm, eta, mode);
    }
    if (!refraction_half_vector(wo, wi, eta, wm)) return 0;
    return ggx_transmission_pdf(g, wo, wi, wm, eta) * (1 - v1_glass_reflect_share(wo, wm, eta, mode));
}

// A direction for the glass from uc (reflection or refraction) and (u1, u2) (the microfacet);
// false when the draw leaves the lobe (GGX's single-scattering loss).
inline bool v1_glass_sample(const Ggx& g, Vec3 wo, float eta, Transport mode, float uc, float u1, float u2, Vec3& wi) {
    const Vec3 wm = g.sample_visible(wo, u1, u2);
    if (uc < v1_glass_reflect_share(wo, wm, eta, mode)) {
        wi = reflect_about(wo, wm);
        return wi.z > 0;
    }
    float etap;
    return refract_about(wo, wm, eta, wi, etap) && wi.z < 0;
}

}  // namespace sl::bsdf
