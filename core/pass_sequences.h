#pragma once
// Low-discrepancy numbers under a random shift, for the camera pass's draws that are stratified
// over the branches of a split path (core/glossy_path.h) or over the passes (a pixel's light
// samples at surfaces and in the haze). The photons' own sequence is core/photon_qmc.h (fixed
// point, walked a batch at a time).
#include <algorithm>
#include <cstdint>

#include "core/rng.h"

namespace sl {

// The base-b radical inverse of k (its digits mirrored about the point), in [0, 1).
inline float radical_inverse(uint32_t k, uint32_t base) {
    float inv = 1.0f / static_cast<float>(base), f = inv, r = 0;
    for (; k > 0; k /= base, f *= inv) r += static_cast<float>(k % base) * f;
    return r;
}
// a + b modulo 1 for a, b in [0, 1), kept below 1 (rounding can land on 1 exactly).
inline float add_mod1(float a, float b) {
    const float x = a + b;
    return std::min(x >= 1.0f ? x - 1.0f : x, 0x1.fffffep-1f);
}
// A pixel's sample of a light in pass `pass`, stratified over the passes: point `pass` of the
// Halton sequence in bases 2 and 3 (and 5, for a third number u3 when asked), shifted modulo 1
// by an offset drawn from the random stream (seed, stream, light, pixel), the same in every
// pass. Each pass's point is uniform (the offset is), so an estimate keeps its mean; over the
// passes the points cover [0, 1)^2 (or ^3) evenly.
inline void halton_pass_point(uint64_t seed, uint64_t stream, uint64_t light, uint64_t pixel, uint32_t pass, float& u1,
                              float& u2, float* u3 = nullptr) {
    Rng offset(seed, stream, light, pixel);
    const float a = offset.uniform(), b = offset.uniform();
    u1 = add_mod1(a, radical_inverse(pass, 2));
    u2 = add_mod1(b, radical_inverse(pass, 3));
    if (u3) *u3 = add_mod1(offset.uniform(), radical_inverse(pass, 5));
}

}  // namespace sl
