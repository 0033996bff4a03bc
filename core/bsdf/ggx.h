#pragma once
// The GGX (Trowbridge-Reitz) microfacet distribution, isotropic, written once for conductors,
// rough dielectrics and the metallic-roughness material. Directions are in the local shading
// frame (the normal is +z). alpha = roughness^2 (the glTF and Blender convention).
// Sampling draws visible normals (Heitz 2018, "Sampling the GGX Distribution of Visible
// Normals"), so every sampled microfacet faces the viewer; masking-shadowing is Smith's
// height-correlated G2.
#include <algorithm>
#include <cmath>

#include "foundation/constants.h"
#include "foundation/vec3.h"

namespace sl::bsdf {

// Below this alpha the lobe is narrower than a float can resolve: clamp (the estimator treats
// such surfaces as specular before it gets here).
inline constexpr float kMinAlpha = 1e-4f;

inline float alpha_of_roughness(float roughness) { return std::max(kMinAlpha, roughness * roughness); }

struct Ggx {
    float alpha = 0.25f;

    // Microfacet normal density D(wm), normalised so that the integral of D(wm) cos(wm) = 1.
    float d(Vec3 wm) const {
        if (wm.z <= 0) return 0;
        const float a2 = alpha * alpha, t = (wm.x * wm.x + wm.y * wm.y) / a2 + wm.z * wm.z;
        return 1 / (kPi * a2 * t * t);
    }
    // Smith's Lambda: the projected area of the back-facing microfacets over that of the front.
    float lambda(Vec3 w) const {
        const float z2 = w.z * w.z, s2 = std::max(0.0f, w.x * w.x + w.y * w.y);
        if (z2 == 0) return INFINITY;
        return (std::sqrt(1 + alpha * alpha * s2 / z2) - 1) / 2;
    }
    float g1(Vec3 w) const { return 1 / (1 + lambda(w)); }
    // Height-correlated masking-shadowing of the pair.
    float g2(Vec3 wo, Vec3 wi) const { return 1 / (1 + lambda(wo) + lambda(wi)); }

    // Density of the normals visible from w (a solid-angle density over wm).
    float d_visible(Vec3 w, Vec3 wm) const {
        const float cz = std::abs(w.z);
        if (cz == 0) return 0;
        return g1(w) / cz * d(wm) * std::abs(dot(w, wm));
    }

    // A visible normal for direction w (either hemisphere; the normal returned has z > 0).
    Vec3 sample_visible(Vec3 w, float u1, float u2) const {
        Vec3 wh = normalize(Vec3(alpha * w.x, alpha * w.y, w.z));
        if (wh.z < 0) wh = -wh;
        const Vec3 t1 = wh.z < 0.99999f ? normalize(cross(Vec3(0, 0, 1), wh)) : Vec3(1, 0, 0);
        const Vec3 t2 = cross(wh, t1);
        // A uniform point on the disk, then squashed onto the visible half of it.
        const float r = std::sqrt(u1), phi = 2 * kPi * u2;
        float p1 = r * std::cos(phi), p2 = r * std::sin(phi);
        const float h = std::sqrt(std::max(0.0f, 1 - p1 * p1)), s = (1 + wh.z) / 2;
        p2 = (1 - s) * h + s * p2;
        const float pz = std::sqrt(std::max(0.0f, 1 - p1 * p1 - p2 * p2));
        const Vec3 nh = t1 * p1 + t2 * p2 + wh * pz;
        return normalize(Vec3(alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)));
    }
};

}  // namespace sl::bsdf
