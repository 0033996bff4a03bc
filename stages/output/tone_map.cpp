#include "stages/output/tone_map.h"

#include <algorithm>
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
    const size_t n = size_t(w) * size_t(h) * 3;
    for (size_t i = 0; i < n; ++i) {
        const double v = exposure * rgb[i];
        // Written so that NaN fails the first test and lands on 0.
        const double c = v > 0 ? std::min(v, 1.0) : 0.0;
        out_rgb8[i] = uint8_t(std::lround(255.0 * srgb_oetf(c)));
    }
}

}  // namespace sl
