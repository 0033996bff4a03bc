#include "stages/output/srgb_byte_table.h"

#include <cmath>
#include <limits>

namespace sl {
namespace {

// IEC 61966-2-1 encoding of a value already in [0, 1].
double srgb_oetf(double v) {
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

}  // namespace

const std::array<double, 257>& SrgbByteTable::lower_bounds() {
    static const std::array<double, 257> lower = [] {
        std::array<double, 257> t{};
        for (int b = 1; b < 256; ++b) {
            double lo = 0, hi = 1;  // smallest c with round(255 * oetf(c)) >= b
            for (int it = 0; it < 60; ++it) {
                double mid = 0.5 * (lo + hi);
                (std::lround(255.0 * srgb_oetf(mid)) >= b ? hi : lo) = mid;
            }
            t[b] = hi;
        }
        t[256] = std::numeric_limits<double>::infinity();  // a sentinel: no byte above 255
        return t;
    }();
    return lower;
}

SrgbByteTable::SrgbByteTable(double exposure) : exposure_(exposure) {
    const auto& lower = lower_bounds();
    // exposure * x >= lower[b] (every lower[b] is in (0, 1], so clamping at 1 changes nothing):
    // false at x = 0, true at x = +inf, monotone in between, and the non-negative floats are
    // ordered as their bits.
    auto reaches = [&](uint32_t bits, double bound) {
        return exposure * static_cast<double>(std::bit_cast<float>(bits)) >= bound;
    };
    at_[0] = 0;
    for (int b = 1; b < 256; ++b) {
        uint32_t lo = at_[b - 1], hi = kInfBits;  // reaches(hi); the answer is above lo or is lo
        if (reaches(lo, lower[b])) {
            at_[b] = lo;
            continue;
        }
        while (hi - lo > 1) {
            const uint32_t mid = lo + (hi - lo) / 2;
            (reaches(mid, lower[b]) ? hi : lo) = mid;
        }
        at_[b] = hi;
    }
    at_[256] = std::numeric_limits<uint32_t>::max();  // above every sanitised value
    // Two thresholds in one bin, the first past the bin's start: a value at the second would
    // start below both.
    for (int b = 2; b < 256; ++b)
        if (at_[b - 1] >> kGuessShift == at_[b] >> kGuessShift && (at_[b - 1] & ((1u << kGuessShift) - 1)) != 0)
            one_step_ = false;
    // guess_[i]: how many thresholds lie at or below the bin's first float, i << kGuessShift.
    guess_.resize((kInfBits >> kGuessShift) + 1);
    uint32_t b = 0;
    for (uint32_t i = 0; i < guess_.size(); ++i) {
        while (b < 255 && at_[b + 1] <= (i << kGuessShift)) ++b;
        guess_[i] = static_cast<uint8_t>(b);
    }
}

}  // namespace sl
