#pragma once
// Sine and cosine of a fraction of a full turn, for sampling directions in hot loops: glibc's
// sincosf was an eighth of the photon pass. The turn is cut into octants, so the polynomials only
// ever see [0, pi/4], where their truncation error (x^11/11!, x^10/10!: below 2e-9) is far under
// a float's rounding; the result is within a few ulp of std::sin/std::cos of 2 pi u.
#include "foundation/constants.h"

namespace sl {

// (cos, sin) of 2 pi u for u in [0, 1). 8u and its fraction are exact in float arithmetic, so
// what rounds is the angle (times pi/4) and the polynomials.
inline void turn_sincos(float u, float& c, float& s) {
    const float a = u * 8;  // exact: a power of two
    const int octant = static_cast<int>(a) & 7;
    const float f = a - static_cast<float>(static_cast<int>(a));  // in [0, 1), exact
    // Odd octants mirror the even ones about their upper edge: sin(pi/2 - x) = cos x.
    const float x = ((octant & 1) ? 1 - f : f) * (kPi / 4);
    const float x2 = x * x;
    const float sx = x * (1 + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
    const float cx = 1 + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320))));
    float cq = cx, sq = sx;  // the angle within its quadrant
    if (octant & 1) { cq = sx; sq = cx; }
    switch (octant >> 1) {  // rotate by the quadrant
        case 0: c = cq; s = sq; break;
        case 1: c = -sq; s = cq; break;
        case 2: c = -cq; s = -sq; break;
        default: c = sq; s = -cq; break;
    }
}

}  // namespace sl
