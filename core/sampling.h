#pragma once
// Warping uniform samples to the directions and points the renderer needs.
#include <cmath>

#include "foundation/constants.h"
#include "foundation/turn_sincos.h"
#include "foundation/vec3.h"

namespace sl {

// Cosine-weighted direction about unit normal n (pdf = cos/pi). Every diffuse bounce of every
// photon takes one: the angle's sine and cosine come from turn_sincos, and the result is not
// normalised again (x^2 + y^2 + z^2 = 1 in an orthonormal basis: its length is 1 to a few ulp).
inline Vec3 sample_cosine_hemisphere(Vec3 n, float u1, float u2) {
    float r = std::sqrt(u1), c, s;
    turn_sincos(u2, c, s);
    float z = std::sqrt(std::max(0.0f, 1 - u1));
    Vec3 t, b;
    make_basis(n, t, b);
    return t * (r * c) + b * (r * s) + n * z;
}

// Uniform direction on the sphere (pdf = 1/4pi).
inline Vec3 sample_uniform_sphere(float u1, float u2) {
    float z = 1 - 2 * u1, r = std::sqrt(std::max(0.0f, 1 - z * z)), phi = 2 * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// Uniform direction in the cone of half-angle acos(cos_max) about unit axis a.
inline Vec3 sample_uniform_cone(Vec3 a, float cos_max, float u1, float u2) {
    float z = 1 - u1 * (1 - cos_max), r = std::sqrt(std::max(0.0f, 1 - z * z)), phi = 2 * kPi * u2;
    Vec3 t, b;
    make_basis(a, t, b);
    return normalize(t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + a * z);
}

// Uniform point on the unit disk (concentric mapping keeps strata intact).
inline void sample_disk(float u1, float u2, float& x, float& y) {
    float a = 2 * u1 - 1, b = 2 * u2 - 1;
    if (a == 0 && b == 0) { x = y = 0; return; }
    float r, phi;
    if (std::abs(a) > std::abs(b)) { r = a; phi = (kPi / 4) * (b / a); }
    else { r = b; phi = kPi / 2 - (kPi / 4) * (a / b); }
    x = r * std::cos(phi);
    y = r * std::sin(phi);
}

}  // namespace sl
