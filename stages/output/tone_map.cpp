#include "stages/output/tone_map.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

#include "stages/output/srgb_byte_table.h"

namespace sl {

namespace {

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

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

// The last exposure's table, shared: frames almost always share one exposure (a table costs
// ~0.1 ms to build), and a caller keeps its table alive while another exposure replaces it.
std::shared_ptr<const SrgbByteTable> table_for(double exposure) {
    static std::mutex mutex;
    static std::shared_ptr<const SrgbByteTable> last;
    std::lock_guard<std::mutex> lock(mutex);
    if (!last || last->exposure() != exposure) last = std::make_shared<const SrgbByteTable>(exposure);
    return last;
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
    const size_t n = size_t(w) * size_t(h) * 3;
    constexpr size_t kGrain = 1 << 14;
    if (curve != ToneCurve::Linear) {
        // The curve first (a log or a rational per value, rounded to float), then its bytes at
        // exposure 1.
        const std::shared_ptr<const SrgbByteTable> table = table_for(1.0);
        const SrgbByteTable::View bytes = table->view();
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kGrain), [=](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i != r.end(); ++i)
                out_rgb8[i] = bytes.byte<false>(static_cast<float>(tone_curve(curve, exposure * rgb[i])));
        });
        return;
    }
    if (!(exposure > 0 && exposure < std::numeric_limits<double>::infinity())) {
        // No table for these (exposure * x is not monotone in x): the formula's bounds, searched.
        const auto& lower = SrgbByteTable::lower_bounds();
        for (size_t i = 0; i < n; ++i) {
            const double v = exposure * rgb[i];
            const double c = v > 0 ? std::min(v, 1.0) : 0.0;  // NaN lands on 0
            out_rgb8[i] = uint8_t(std::upper_bound(lower.begin() + 1, lower.begin() + 256, c) - lower.begin() - 1);
        }
        return;
    }
    // The bytes from the values' float bits (srgb_byte_table.h): a 256x256 frame took ~1 ms
    // with a double product, a float guess and double compares per value.
    const std::shared_ptr<const SrgbByteTable> table = table_for(exposure);
    const SrgbByteTable::View bytes = table->view();  // plain pointers, copied into the lambda
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kGrain), [=](const tbb::blocked_range<size_t>& r) {
        if (bytes.one_step)
            for (size_t i = r.begin(); i != r.end(); ++i) out_rgb8[i] = bytes.byte<true>(rgb[i]);
        else
            for (size_t i = r.begin(); i != r.end(); ++i) out_rgb8[i] = bytes.byte<false>(rgb[i]);
    });
}

}  // namespace sl
