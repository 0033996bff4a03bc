#pragma once
// How light leaves a surface, shared by camera paths and photon paths. Diffuse surfaces are
// two-sided Lambertian; mirrors reflect; dielectrics reflect or refract by Fresnel.
#include <cmath>

#include "core/material_table.h"
#include "core/rng.h"
#include "core/sampling.h"

namespace sl {

inline Vec3 reflect(Vec3 d, Vec3 n) { return d - n * (2 * dot(d, n)); }

// Unpolarised Fresnel reflectance for a dielectric interface; eta = n_incident / n_transmitted.
inline float fresnel_dielectric(float cos_i, float eta, float& cos_t) {
    float sin2_t = eta * eta * std::max(0.0f, 1 - cos_i * cos_i);
    if (sin2_t >= 1) { cos_t = 0; return 1; }  // total internal reflection
    cos_t = std::sqrt(1 - sin2_t);
    float rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    float rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5f * (rs * rs + rp * rp);
}

struct SpecularBounce {
    Vec3 direction;
    Vec3 weight;          // throughput multiplier
    bool inside_after;    // the path now travels inside the dielectric
};

// A specular event (mirror or dielectric) for a path arriving along d at a surface with unit
// geometric normal n. For dielectrics the choice of reflection or refraction is sampled.
inline SpecularBounce specular_bounce(const SurfaceMaterial& m, Vec3 d, Vec3 n, bool inside, Rng& rng) {
    Vec3 nf = dot(d, n) < 0 ? n : -n;  // faces the arriving path
    if (m.type == MaterialType::Mirror) return {reflect(d, nf), m.reflectance, inside};
    float eta = inside ? m.ior : 1.0f / m.ior;
    float cos_i = -dot(d, nf), cos_t = 0;
    float f = fresnel_dielectric(cos_i, eta, cos_t);
    if (rng.uniform() < f) return {reflect(d, nf), Vec3(1), inside};
    Vec3 t = d * eta + nf * (eta * cos_i - cos_t);
    // Radiance scales by eta^2 across the interface; photon flux does not. Both paths use
    // this for flux and importance alike, which keeps camera and photon paths consistent.
    return {normalize(t), Vec3(1), !inside};
}

}  // namespace sl
