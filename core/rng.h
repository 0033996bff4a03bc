#pragma once
// PCG32 random numbers, seeded from a tuple of integers so that every pixel, pass and photon
// batch has its own stream: results do not depend on thread count or scheduling.
#include <cstdint>

namespace sl {

inline uint64_t mix64(uint64_t x) {  // splitmix64 finaliser
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

class Rng {
public:
    Rng(uint64_t seed, uint64_t a, uint64_t b = 0, uint64_t c = 0) {
        uint64_t s = mix64(seed ^ mix64(a ^ mix64(b ^ mix64(c))));
        inc_ = (mix64(s + 1) << 1) | 1u;
        state_ = 0;
        next_u32();
        state_ += s;
        next_u32();
    }
    uint32_t next_u32() {
        uint64_t old = state_;
        state_ = old * 6364136223846793005ull + inc_;
        uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        uint32_t rot = static_cast<uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
    }
    // Uniform in [0, 1): 24 random bits, so the result is never rounded up to 1. The numbers
    // given to use_first come first, in order.
    float uniform() {
        if (first_left_ > 0) {
            --first_left_;
            return *first_++;
        }
        return static_cast<float>(next_u32() >> 8) * 0x1p-24f;
    }
    // The next n numbers uniform() returns are u[0..n) (kept by the caller), then its own again:
    // a photon path's first numbers from a low-discrepancy point (photon_qmc.h).
    void use_first(const float* u, int n) {
        first_ = u;
        first_left_ = n;
    }

private:
    uint64_t state_, inc_;
    const float* first_ = nullptr;
    int first_left_ = 0;
};

}  // namespace sl
