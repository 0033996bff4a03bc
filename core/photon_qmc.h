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

    static constexpr uint32_t kPrime[kDims] = {2, 3, 5, 7, 11, 13, 17, 19};

    // The point of photon `index` of the pass: kDims numbers in [0, 1).
    void point(uint64_t index, float* u) const {
        for (int j = 0; j < kDims; ++j) u[j] = shifted(radical_inverse(index, kPrime[j]), j);
    }

    // v in [0, 1) moved by dimension j's shift, modulo 1, kept below 1 against rounding.
    float shifted(float v, int j) const {
        constexpr float kBelow1 = 0x1.fffffep-1f;
        v += shift_[j];
        if (v >= 1.0f) v -= 1.0f;
        return std::min(std::max(v, 0.0f), kBelow1);
    }

    // The points of consecutive indices from `first` on, one at a time: each dimension keeps its
    // digits and adds one to them (amortised a digit a point), which costs a few operations
    // where point() divides ~8 times per dimension (a tenth of a diffuse scene's time). Every
    // batch of photons starts its own walk at its first index: threads and ranks agree.
    class Walk {
    public:
        Walk(const PhotonQmc& q, uint64_t first) : q_(q) {
            for (int j = 0; j < kDims; ++j) {
                const uint32_t b = kPrime[j];
                double scale = 1.0 / b;
                value_[j] = 0;
                uint64_t i = first;
                for (int k = 0; k < kDigits; ++k, scale /= b, i /= b) {
                    digit_[j][k] = static_cast<uint8_t>(i % b);
                    scale_[j][k] = scale;
                    value_[j] += digit_[j][k] * scale;
                }
            }
        }
        // The current index's point, then on to the next index.
        void next(float* u) {
            for (int j = 0; j < kDims; ++j) {
                u[j] = q_.shifted(static_cast<float>(value_[j]), j);
                const uint8_t last = static_cast<uint8_t>(kPrime[j] - 1);
                for (int k = 0; k < kDigits; ++k) {
                    if (digit_[j][k] < last) {
                        ++digit_[j][k];
                        value_[j] += scale_[j][k];
                        break;
                    }
                    digit_[j][k] = 0;
                    value_[j] -= last * scale_[j][k];
                }
            }
        }

    private:
        static constexpr int kDigits = 40;  // 2^40 indices in base 2, more in the others
        const PhotonQmc& q_;
        double value_[kDims];
        double scale_[kDims][kDigits];
        uint8_t digit_[kDims][kDigits];
    };

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
