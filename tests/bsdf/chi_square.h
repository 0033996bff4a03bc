#pragma once
// Pearson's chi-square goodness-of-fit of a sampler's histogram against the counts its pdf
// predicts, in the manner of Mitsuba 3's chi2 test: cells whose expected count is below 5 are
// pooled into one, a sample in a cell the pdf gives (almost) nothing fails at once, and the
// p-value of the statistic is compared with a significance level corrected for the number of
// tests run (Sidak).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace sl::test {

struct ChiSquareResult {
    double statistic = 0, p_value = 0;
    int dof = 0;
    std::string failure;  // non-empty: a sample where the pdf says none can be
};

// The upper tail of the chi-square distribution with k degrees of freedom beyond x, by the
// Wilson-Hilferty cube-root normal approximation (accurate to ~1e-3 for k in the hundreds).
inline double chi_square_tail(double x, int k) {
    const double h = 2.0 / (9.0 * k), z = (std::cbrt(x / k) - (1 - h)) / std::sqrt(h);
    return 0.5 * std::erfc(z / std::sqrt(2.0));
}

inline ChiSquareResult chi_square(const std::vector<double>& observed, const std::vector<double>& expected) {
    ChiSquareResult r;
    std::vector<size_t> order(observed.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });
    double pool_obs = 0, pool_exp = 0;
    int cells = 0;
    for (size_t i : order) {
        if (expected[i] < 1e-5 && observed[i] > 0) {
            r.failure = "cell " + std::to_string(i) + " has " + std::to_string(observed[i]) +
                        " samples where the pdf expects " + std::to_string(expected[i]);
            return r;
        }
        if (expected[i] < 5) {
            pool_obs += observed[i];
            pool_exp += expected[i];
            continue;
        }
        const double d = observed[i] - expected[i];
        r.statistic += d * d / expected[i];
        ++cells;
    }
    if (pool_exp >= 5) {
        const double d = pool_obs - pool_exp;
        r.statistic += d * d / pool_exp;
        ++cells;
    } else if (!order.empty()) {  // too little to test: fold it into the last (largest) cell
        const size_t big = order.back();
        const double d0 = observed[big] - expected[big], d1 = d0 + pool_obs - pool_exp;
        r.statistic += d1 * d1 / (expected[big] + pool_exp) - d0 * d0 / expected[big];
    }
    r.dof = std::max(1, cells - 1);
    r.p_value = chi_square_tail(r.statistic, r.dof);
    return r;
}

}  // namespace sl::test
