#include "stages/output/tone_map.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
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

void tone_map_srgb8(const float* rgb, int w, int h, double exposure, uint8_t* out_rgb8) {
    // The sRGB curve without a pow per value: for every byte b, the smallest linear value that
    // rounds to it; a binary search over these 256 boundaries gives the formula's byte.
    static const std::array<double, 256> lower = [] {
        std::array<double, 256> t{};
        t[0] = 0;
        for (int b = 1; b < 256; ++b) {
            double lo = 0, hi = 1;  // smallest c with round(255 * oetf(c)) >= b
            for (int it = 0; it < 60; ++it) {
                double mid = 0.5 * (lo + hi);
                (std::lround(255.0 * srgb_oetf(mid)) >= b ? hi : lo) = mid;
            }
            t[b] = hi;
        }
        return t;
    }();
    const size_t n = size_t(w) * size_t(h) * 3;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const double v = exposure * rgb[i];
            // Written so that NaN fails the first test and lands on 0.
            const double c = v > 0 ? std::min(v, 1.0) : 0.0;
            out_rgb8[i] = uint8_t(std::upper_bound(lower.begin() + 1, lower.end(), c) - lower.begin() - 1);
        }
    });
}

}  // namespace sl
