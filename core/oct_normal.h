#pragma once
// Unit normals in 4 bytes (octahedral mapping, two 16-bit coordinates) instead of 12: photon
// records and visible points hold one each, and they are the memory that does not shrink with
// the number of sections. The angular error is below 1e-4 rad; the gather only compares
// normals against a 45-degree threshold.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "foundation/vec3.h"

namespace sl {

struct OctNormal {
    int16_t u = 0, v = 0;
};

namespace oct_detail {
inline float sign_not_zero(float a) { return a >= 0 ? 1.0f : -1.0f; }
// std::lround, inline: every photon record encodes a normal, and the library call was a few
// percent of the photon pass. Exact: a float minus its integer part is exact, so halves round
// away from zero as lround does (|v| <= 32767 here).
inline int32_t round_half_away(float v) {
    const int32_t i = static_cast<int32_t>(v);  // toward zero
    const float frac = v - static_cast<float>(i);
    return i + (frac >= 0.5f) - (frac <= -0.5f);
}
inline int16_t quantize(float a) {
    return static_cast<int16_t>(round_half_away(std::clamp(a, -1.0f, 1.0f) * 32767.0f));
}
}  // namespace oct_detail

// n must be unit length (or at least not zero).
inline OctNormal encode_normal(Vec3 n) {
    using namespace oct_detail;
    const float l1 = std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z);
    float u = n.x / l1, v = n.y / l1;
    if (n.z < 0) {  // fold the lower half onto the corners of the square
        const float fu = (1 - std::fabs(v)) * sign_not_zero(u);
        const float fv = (1 - std::fabs(u)) * sign_not_zero(v);
        u = fu;
        v = fv;
    }
    return {quantize(u), quantize(v)};
}

// Not normalised: a vector along the normal with length in [1/sqrt(3), 1].
inline Vec3 decode_normal_unnormalized(OctNormal o) {
    const float u = o.u * (1.0f / 32767.0f), v = o.v * (1.0f / 32767.0f);
    const float z = 1 - std::fabs(u) - std::fabs(v);
    if (z >= 0) return {u, v, z};
    return {(1 - std::fabs(v)) * oct_detail::sign_not_zero(u), (1 - std::fabs(u)) * oct_detail::sign_not_zero(v), z};
}

inline Vec3 decode_normal(OctNormal o) { return normalize(decode_normal_unnormalized(o)); }

}  // namespace sl
