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
        for (uint32_t& s : shift_) s = rng.next_u32();
    }

    static constexpr uint32_t kPrime[kDims] = {2, 3, 5, 7, 11, 13, 17, 19};

    // The point of photon `index` of the pass: kDims numbers in [0, 1).
    void point(uint64_t index, float* u) const {
        for (int j = 0; j < kDims; ++j) u[j] = shifted(radical_inverse_fixed(index, kPrime[j]), j);
    }

    // A fixed-point value (units of 2^-32) moved by dimension j's shift: the sum wraps modulo
    // 2^32, which is the shift modulo 1 without a branch (a branch here was mispredicted half
    // the time), then its top 24 bits as a float below 1.
    float shifted(uint32_t v, int j) const { return static_cast<float>((v + shift_[j]) >> 8) * 0x1p-24f; }

    static constexpr int kDigits = 40;  // 2^40 indices in base 2, more in the others

    // Digit k's weight in base kPrime[j], b^-(k+1), in units of 2^-32 rounded down (0 once below
    // them), made once: a radical inverse is the sum of its digits' weights, exact in integers,
    // so a walk's additions and subtractions give exactly the point's value.
    using DigitWeights = uint32_t[kDims][kDigits];
    static const DigitWeights& digit_weights() {
        static const auto table = [] {
            struct Table {
                DigitWeights w;
            } t{};
            for (int j = 0; j < kDims; ++j) {
                uint64_t p = kPrime[j];  // b^(k+1)
                for (int k = 0; k < kDigits && p <= (uint64_t(1) << 32); ++k, p *= kPrime[j])
                    t.w[j][k] = static_cast<uint32_t>((uint64_t(1) << 32) / p);
            }
            return t;
        }();
        return table.w;
    }

    // The points of consecutive indices from `first` on: each dimension keeps its digits and
    // adds one to them (amortised a digit a point), which costs a few operations where point()
    // divides ~8 times per dimension (a tenth of a diffuse scene's time). Every batch of photons
    // starts its own walk at its first index: threads and ranks agree.
    class Walk {
    public:
        Walk(const PhotonQmc& q, uint64_t first) : q_(q), weight_(digit_weights()) {
            for (int j = 0; j < kDims; ++j) {
                value_[j] = 0;
                uint64_t i = first;
                for (int k = 0; k < kDigits; ++k, i /= kPrime[j]) {
                    digit_[j][k] = static_cast<uint8_t>(i % kPrime[j]);
                    value_[j] += digit_[j][k] * weight_[j][k];
                }
            }
        }
        // The points of the next n indices, kDims numbers each, into u[0 .. n kDims): dimension
        // by dimension, so that each dimension's carries come in their own regular rhythm (base b:
        // one in b) that the branch predictor learns, instead of mixed with the photon paths'
        // branches between two points.
        void fill(float* u, int n) {
            for (int j = 0; j < kDims; ++j) {
                const uint8_t last = static_cast<uint8_t>(kPrime[j] - 1);
                uint32_t value = value_[j];
                uint8_t* digit = digit_[j];
                const uint32_t* weight = weight_[j];
                for (int i = 0; i < n; ++i) {
                    u[i * kDims + j] = q_.shifted(value, j);
                    for (int k = 0; k < kDigits; ++k) {
                        if (digit[k] < last) {
                            ++digit[k];
                            value += weight[k];
                            break;
                        }
                        digit[k] = 0;
                        value -= last * weight[k];
                    }
                }
                value_[j] = value;
            }
        }
        // The current index's point, then on to the next index.
        void next(float* u) { fill(u, 1); }

    private:
        const PhotonQmc& q_;
        const DigitWeights& weight_;
        uint32_t value_[kDims];
        uint8_t digit_[kDims][kDigits];
    };

    // index's digits in base b (one of kPrime) mirrored about the point: 0.d1 d2 d3..., in
    // units of 2^-32.
    static uint32_t radical_inverse_fixed(uint64_t index, uint32_t base) {
        const int j = static_cast<int>(std::find(kPrime, kPrime + kDims, base) - kPrime);
        if (j == kDims) return 0;  // not one of the sequence's bases
        uint32_t r = 0;
        for (int k = 0; index > 0 && k < kDigits; index /= base, ++k)
            r += static_cast<uint32_t>(index % base) * digit_weights()[j][k];
        return r;
    }
    static float radical_inverse(uint64_t index, uint32_t base) {
        return static_cast<float>(radical_inverse_fixed(index, base) >> 8) * 0x1p-24f;
    }

private:
    uint32_t shift_[kDims];
};

}  // namespace sl
