#pragma once
// Fresnel reflectance, written once for every BSDF: the exact unpolarised equations for a
// dielectric interface and for a conductor (complex index eta + i k), and Schlick's
// approximation from the reflectance at normal incidence F0 (glTF's metals: base colour = F0).
#include <algorithm>
#include <cmath>
#include <complex>

#include "foundation/vec3.h"

namespace sl::bsdf {

// Reflectance of a dielectric interface for light arriving at cos_i to its normal, from the
// side the normal points to; eta = n_other / n_this (the index across the interface relative
// to the side of cos_i > 0). A negative cos_i means arrival from the other side (eta inverts).
// Total internal reflection gives 1.
inline float fresnel_dielectric(float cos_i, float eta) {
    cos_i = std::clamp(cos_i, -1.0f, 1.0f);
    if (cos_i < 0) { eta = 1 / eta; cos_i = -cos_i; }
    const float sin2_i = 1 - cos_i * cos_i, sin2_t = sin2_i / (eta * eta);
    if (sin2_t >= 1) return 1;
    const float cos_t = std::sqrt(std::max(0.0f, 1 - sin2_t));
    const float r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5f * (r_par * r_par + r_perp * r_perp);
}

// Reflectance of a conductor with complex index eta + i k (relative to the outside medium),
// for one wavelength; cos_i in [0, 1].
inline float fresnel_complex(float cos_i, float eta, float k) {
    using C = std::complex<float>;
    cos_i = std::clamp(cos_i, 0.0f, 1.0f);
    const C n(eta, k);
    const float sin2_i = 1 - cos_i * cos_i;
    const C sin2_t = sin2_i / (n * n), cos_t = std::sqrt(C(1) - sin2_t);
    const C r_par = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    const C r_perp = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    return 0.5f * (std::norm(r_par) + std::norm(r_perp));
}

inline Vec3 fresnel_conductor(float cos_i, Vec3 eta, Vec3 k) {
    return {fresnel_complex(cos_i, eta.x, k.x), fresnel_complex(cos_i, eta.y, k.y), fresnel_complex(cos_i, eta.z, k.z)};
}

// Schlick's approximation F0 + (1 - F0)(1 - cos)^5.
inline Vec3 fresnel_schlick(Vec3 f0, float cos_i) {
    const float m = std::clamp(1 - std::abs(cos_i), 0.0f, 1.0f), m5 = (m * m) * (m * m) * m;
    return f0 + (Vec3(1) - f0) * m5;
}

// Reflectance at normal incidence of a dielectric of relative index eta: ((eta-1)/(eta+1))^2.
inline float f0_of_ior(float eta) {
    const float r = (eta - 1) / (eta + 1);
    return r * r;
}

}  // namespace sl::bsdf
