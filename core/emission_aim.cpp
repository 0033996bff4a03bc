#include "core/emission_aim.h"

#include <algorithm>
#include <cmath>

namespace sl {

EmissionAim::EmissionAim(int n, const std::vector<double>& usefulness, double floor) {
    if (n <= 0 || usefulness.size() != static_cast<size_t>(n) * n) return;
    double total = 0;
    for (double u : usefulness) total += std::isfinite(u) && u > 0 ? u : 0;
    if (!(total > 0)) return;
    n_ = n;
    const size_t cells = static_cast<size_t>(n) * n;
    prob_.resize(cells);
    for (size_t c = 0; c < cells; ++c) {
        const double u = std::isfinite(usefulness[c]) && usefulness[c] > 0 ? usefulness[c] : 0;
        prob_[c] = (1 - floor) * u / total + floor / static_cast<double>(cells);
    }
    row_cdf_.assign(static_cast<size_t>(n) + 1, 0.0f);
    col_cdf_.assign(static_cast<size_t>(n) * (n + 1), 0.0f);
    double run = 0;
    for (int j = 0; j < n; ++j) {
        double row = 0;
        for (int i = 0; i < n; ++i) row += prob_[static_cast<size_t>(j) * n + i];
        double in_row = 0;
        float* col = &col_cdf_[static_cast<size_t>(j) * (n + 1)];
        for (int i = 0; i < n; ++i) {
            in_row += prob_[static_cast<size_t>(j) * n + i];
            col[i + 1] = static_cast<float>(in_row / row);
        }
        col[n] = 1.0f;
        run += row;
        row_cdf_[static_cast<size_t>(j) + 1] = static_cast<float>(run);
    }
    row_cdf_[static_cast<size_t>(n)] = 1.0f;
}

namespace {
// The bin of a cdf (size n + 1, from 0 to 1) that holds u, and u's place within it in [0, 1).
// The bin's width is returned in `width`: the flux factor uses the probabilities the floats give.
int invert(const float* cdf, int n, float u, float& within, float& width) {
    int k = static_cast<int>(std::upper_bound(cdf + 1, cdf + n + 1, u) - (cdf + 1));
    k = std::min(k, n - 1);
    while (k > 0 && cdf[k + 1] == cdf[k]) --k;  // never an empty bin (the floor makes none, but rounding might)
    width = cdf[k + 1] - cdf[k];
    within = width > 0 ? std::clamp((u - cdf[k]) / width, 0.0f, 0x1.fffffep-1f) : 0.5f;
    return k;
}
}  // namespace

float EmissionAim::draw(float u1, float u2, float& x, float& y) const {
    if (n_ == 0) {
        x = u1;
        y = u2;
        return 1.0f;
    }
    float fy, fx, wy, wx;
    const int j = invert(row_cdf_.data(), n_, u2, fy, wy);
    const int i = invert(&col_cdf_[static_cast<size_t>(j) * (n_ + 1)], n_, u1, fx, wx);
    x = (static_cast<float>(i) + fx) / static_cast<float>(n_);
    y = (static_cast<float>(j) + fy) / static_cast<float>(n_);
    return static_cast<float>(1.0 / (static_cast<double>(wy) * wx * static_cast<double>(n_) * n_));
}

}  // namespace sl
