#pragma once
// GGX's single-scattering lobes without Fresnel, shared by every microfacet BSDF: reflection
// D G2 / (4 cos_o cos_i), Walter et al.'s transmission (radiance or importance), their
// visible-normal sampling densities, and the mirror and refraction of a direction about a normal.
// Directions are in the local shading frame (normal +z).
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/bsdf/ggx.h"
#include "foundation/vec3.h"

namespace sl::bsdf {

// Radiance (camera paths) or importance (photons); see bsdf.h's header comment.
enum class Transport : uint8_t { Radiance, Importance };

inline Vec3 reflect_about(Vec3 wo, Vec3 n) { return n * (2 * dot(wo, n)) - wo; }

// Refraction of wo through a surface of normal n (wo on either side); eta = n_other / n_wo-side
// relative to n's side. False on total internal reflection. etap: the index ratio used.
inline bool refract_about(Vec3 wo, Vec3 n, float eta, Vec3& wt, float& etap) {
    float cos_i = dot(n, wo);
    if (cos_i < 0) { eta = 1 / eta; cos_i = -cos_i; n = -n; }
    const float sin2_t = std::max(0.0f, 1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1) return false;
    const float cos_t = std::sqrt(1 - sin2_t);
    wt = -wo / eta + n * (cos_i / eta - cos_t);
    etap = eta;
    return true;
}

// The GGX reflection lobe without Fresnel: D G2 / (4 cos_o cos_i), and its sampling density
// (both directions on the +z side).
inline float ggx_reflection(const Ggx& g, Vec3 wo, Vec3 wi, Vec3& wm) {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    wm = wo + wi;
    if (dot(wm, wm) == 0) return 0;
    wm = normalize(wm);
    return g.d(wm) * g.g2(wo, wi) / (4 * wo.z * wi.z);
}
inline float ggx_reflection_pdf(const Ggx& g, Vec3 wo, Vec3 wm) {
    const float c = dot(wo, wm);
    return c > 0 ? g.d_visible(wo, wm) / (4 * c) : 0;
}

// The half vector of a refraction pair (wo outside-side per etap), oriented to +z; false when
// the pair cannot be a refraction through a front-facing microfacet.
inline bool refraction_half_vector(Vec3 wo, Vec3 wi, float etap, Vec3& wm) {
    wm = wi * etap + wo;
    if (wi.z == 0 || wo.z == 0 || dot(wm, wm) == 0) return false;
    wm = normalize(wm);
    if (wm.z < 0) wm = -wm;
    return dot(wm, wi) * wi.z > 0 && dot(wm, wo) * wo.z > 0;
}

// GGX transmission without the (1 - F) factor, radiance or importance; etap as above.
inline float ggx_transmission(const Ggx& g, Vec3 wo, Vec3 wi, Vec3 wm, float etap, Transport mode) {
    const float a = dot(wi, wm) + dot(wo, wm) / etap;
    const float denom = a * a * wi.z * wo.z;
    float f = g.d(wm) * g.g2(wo, wi) * std::abs(dot(wi, wm) * dot(wo, wm) / denom);
    if (mode == Transport::Radiance) f /= etap * etap;
    return f;
}
inline float ggx_transmission_pdf(const Ggx& g, Vec3 wo, Vec3 wi, Vec3 wm, float etap) {
    const float a = dot(wi, wm) + dot(wo, wm) / etap;
    return g.d_visible(wo, wm) * std::abs(dot(wi, wm)) / (a * a);
}

}  // namespace sl::bsdf
