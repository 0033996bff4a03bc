#include "stages/output/tone_map.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <limits>
#include <cmath>
#include <cstddef>
#include <vector>

namespace sl {

namespace {

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

// IEC 61966-2-1 encoding of a value already in [0, 1].
double srgb_oetf(double v) {
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

}  // namespace

double exposure_from_steady(const float* rgb, int w, int h) {
    const size_t n = size_t(w) * size_t(h);
    std::vector<double> lum;
    lum.reserve(n);
    for (size_t i = 0; i < n; ++i) {
        const double y = luminance(rgb + 3 * i);
        if (std::isfinite(y)) lum.push_back(y);
    }
    if (lum.empty()) return 1.0;

    // Nearest-rank percentile: the smallest value with at least 99% of the pixels at or below it.
    const size_t rank = size_t(std::ceil(0.99 * double(lum.size())));
    const size_t k = std::clamp<size_t>(rank, 1, lum.size()) - 1;
    std::nth_element(lum.begin(), lum.begin() + ptrdiff_t(k), lum.end());
    double reference = lum[k];
    // A mostly black image (e.g. a laser dot): expose for the brightest pixel instead.
    if (!(reference > 0)) reference = *std::max_element(lum.begin() + ptrdiff_t(k), lum.end());
    return reference > 0 ? 1.0 / reference : 1.0;
}

namespace {

// For every byte b, the smallest linear value that rounds to it under the sRGB formula.
const std::array<double, 257>& byte_lower_bounds() {
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

// A first guess indexed by a float's exponent and top 7 mantissa bits (bins of 1/128 relative
// width, at most about half a byte wide on the curve): the byte of the bin's lowest value.
constexpr int kGuessShift = 16;
const std::vector<uint8_t>& byte_guess() {
    static const std::vector<uint8_t> guess = [] {
        const auto& lower = byte_lower_bounds();
        const uint32_t last = std::bit_cast<uint32_t>(1.0f) >> kGuessShift;
        std::vector<uint8_t> g(last + 1);
        for (uint32_t i = 0; i <= last; ++i) {
            const double c = std::bit_cast<float>(i << kGuessShift);
            g[i] = uint8_t(std::upper_bound(lower.begin() + 1, lower.begin() + 256, c) - lower.begin() - 1);
        }
        return g;
    }();
    return guess;
}

}  // namespace

double tone_curve(ToneCurve curve, double v) {
    if (!(v > 0)) return 0.0;  // NaN too
    switch (curve) {
    case ToneCurve::Filmic: return std::min(1.0, v * (2.51 * v + 0.03) / (v * (2.43 * v + 0.59) + 0.14));
    case ToneCurve::Log: return std::min(1.0, std::log1p(16.0 * v) / std::log1p(64.0));
    case ToneCurve::Linear: break;
    }
    return std::min(v, 1.0);
}

void tone_map_srgb8(const float* rgb, int w, int h, double exposure, uint8_t* out_rgb8, ToneCurve curve) {
    if (curve != ToneCurve::Linear) {
        // The curve first (a log or a rational per value), then the exact sRGB bytes below.
        const size_t n = size_t(w) * size_t(h) * 3;
        std::vector<float> curved(n);
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i != r.end(); ++i)
                curved[i] = static_cast<float>(tone_curve(curve, exposure * rgb[i]));
        });
        tone_map_srgb8(curved.data(), w, h, 1.0, out_rgb8, ToneCurve::Linear);
        return;
    }
    // The sRGB curve without a pow or a search per value: a table guess from the value's float
    // bits, then a step or two against the exact boundaries (in double), so every byte is the
    // formula's own. (A binary search per value cost ~30 ms a frame at 512x512.)
    // Plain locals: stores through the uint8_t output may alias anything the lambda reads through
    // a reference, which would make the compiler reload it for every value.
    const double* const lower = byte_lower_bounds().data();
    const uint8_t* const guess = byte_guess().data();
    const size_t n = size_t(w) * size_t(h) * 3;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [=](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const double v = exposure * rgb[i];
            // Written so that NaN fails the first test and lands on 0.
            const double c = v > 0 ? std::min(v, 1.0) : 0.0;
            // c rounded down to float (one ulp back if the cast went up; c >= 0): its bin's guess
            // is then at or below the answer.
            const float cf = static_cast<float>(c);
            const uint32_t bits = std::bit_cast<uint32_t>(cf) - (cf > c ? 1u : 0u);
            int b = guess[bits >> kGuessShift];
            b += c >= lower[b + 1];  // a bin spans at most one boundary: branch-free steps,
            b += c >= lower[b + 1];  // and a loop that in practice never runs
            while (c >= lower[b + 1]) ++b;
            out_rgb8[i] = uint8_t(b);
        }
    });
}

}  // namespace sl
