#pragma once
// IEEE 754 binary16 ("half") conversions, by hand so that core/ needs no image library: HDR
// textures are stored as halves (6 bytes a texel instead of 12). Round to nearest even; values
// past 65504 become infinity, which the texture loader never stores (it clamps first).
#include <cstdint>
#include <cstring>

namespace sl {

inline float half_to_float(uint16_t h) {
    const uint32_t sign = static_cast<uint32_t>(h & 0x8000u) << 16;
    uint32_t exp = (h >> 10) & 0x1fu, man = h & 0x3ffu, bits;
    if (exp == 0) {
        if (man == 0) {
            bits = sign;
        } else {  // subnormal: normalise
            exp = 127 - 15 + 1;
            while (!(man & 0x400u)) { man <<= 1; --exp; }
            bits = sign | (exp << 23) | ((man & 0x3ffu) << 13);
        }
    } else if (exp == 31) {
        bits = sign | 0x7f800000u | (man << 13);
    } else {
        bits = sign | ((exp + 127 - 15) << 23) | (man << 13);
    }
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
}

inline uint16_t float_to_half(float f) {
    uint32_t x;
    std::memcpy(&x, &f, 4);
    const uint16_t sign = static_cast<uint16_t>((x >> 16) & 0x8000u);
    const uint32_t abs = x & 0x7fffffffu;
    if (abs >= 0x7f800000u) return static_cast<uint16_t>(sign | 0x7c00u | (abs > 0x7f800000u ? 0x200u : 0u));
    if (abs >= 0x477ff000u) return static_cast<uint16_t>(sign | 0x7c00u);  // rounds past 65504
    if (abs < 0x33000001u) return sign;                                     // below half the smallest subnormal
    int exp = static_cast<int>(abs >> 23);
    uint32_t man = (abs & 0x7fffffu) | 0x800000u;
    // Shift so that the half's mantissa (10 bits, plus the hidden bit) is left, rounding to even.
    const int shift = exp < 113 ? 13 + 113 - exp : 13;
    const uint32_t rest = man & ((1u << shift) - 1), half_way = 1u << (shift - 1);
    uint32_t m = man >> shift;
    if (rest > half_way || (rest == half_way && (m & 1u))) ++m;
    if (exp < 113) return static_cast<uint16_t>(sign | m);  // subnormal (a carry into 0x400 is the smallest normal)
    return static_cast<uint16_t>(sign | ((static_cast<uint32_t>(exp - 112) << 10) + (m - 0x400u)));
}

}  // namespace sl
