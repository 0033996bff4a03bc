#pragma once
// The first random numbers of every photon path from a randomised Halton sequence. A pass's
// photons then cover the light's position and direction, and their first bounce, far more
// evenly than independent draws would: a region lit by few photons (a face in shadow, lit by
// the floor in front of it) sees far less noise from pass to pass. Each pass shifts the whole
// point set by its own random offset (mod 1: Cranley-Patterson), so every photon's numbers are
// still uniform and independent of the other passes', and the estimate stays unbiased. The
// index is the photon's place in its pass, so ranks and threads give the same photons.
#include <algorithm>
#include <cstdint>

#include "core/rng.h"

namespace sl {

class PhotonQmc {
public:
    static constexpr int kDims = 8;  // light choice, position, direction, the first bounce

    PhotonQmc(uint64_t seed, uint64_t pass) {
        Rng rng(seed, 3, pass);
        for (float& s : shift_) s = rng.uniform();
    }

    // The point of photon `index` of the pass: kDims numbers in [0, 1).
    void point(uint64_t index, float* u) const {
        static constexpr uint32_t kPrime[kDims] = {2, 3, 5, 7, 11, 13, 17, 19};
        constexpr float kBelow1 = 0x1.fffffep-1f;
        for (int j = 0; j < kDims; ++j) {
            float v = radical_inverse(index, kPrime[j]) + shift_[j];
            if (v >= 1.0f) v -= 1.0f;
            u[j] = std::min(v, kBelow1);
        }
    }

    // index's digits in base b mirrored about the point: 0.d1 d2 d3... (double: indices up to 2^53).
    static float radical_inverse(uint64_t index, uint32_t base) {
        const double inv = 1.0 / base;
        double f = inv, r = 0;
        for (; index > 0; index /= base, f *= inv) r += static_cast<double>(index % base) * f;
        return static_cast<float>(r);
    }

private:
    float shift_[kDims];
};

}  // namespace sl
