#pragma once
// The sphere cut into cells of equal solid angle (cos theta and phi bins) and integrated per
// cell by Gauss-Legendre quadrature in (theta, phi): theta rather than cos theta, because the
// lobes of rough surfaces are smooth in theta but crowd into the last cos-theta bin at the
// pole. The chi-square test integrates pdf() with it; the furnace and weight tests f cos.
#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "foundation/constants.h"
#include "foundation/vec3.h"

namespace sl::test {

struct SphereGrid {
    int cos_bins = 36, phi_bins = 72;
    int cells() const { return cos_bins * phi_bins; }
    int cell_of(Vec3 w) const {
        const float c = std::clamp(w.z, -1.0f, 1.0f);
        int i = static_cast<int>((c + 1) / 2 * cos_bins);
        float phi = std::atan2(w.y, w.x);
        if (phi < 0) phi += 2 * kPi;
        int j = static_cast<int>(phi / (2 * kPi) * phi_bins);
        i = std::clamp(i, 0, cos_bins - 1);
        j = std::clamp(j, 0, phi_bins - 1);
        return i * phi_bins + j;
    }
};

// 16-point Gauss-Legendre nodes and weights on [-1, 1].
inline const std::array<std::array<double, 2>, 16>& gauss_legendre16() {
    static const std::array<std::array<double, 2>, 16> nw = [] {
        std::array<std::array<double, 2>, 16> r{};
        const int n = 16;
        for (int i = 0; i < n; ++i) {  // Newton's method on P_n from the Chebyshev guess
            double x = std::cos(kPiDouble * (i + 0.75) / (n + 0.5)), dp = 0;
            for (int it = 0; it < 100; ++it) {
                double p0 = 1, p1 = x;
                for (int k = 2; k <= n; ++k) {
                    const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n * (x * p1 - p0) / (x * x - 1);
                const double dx = p1 / dp;
                x -= dx;
                if (std::abs(dx) < 1e-15) break;
            }
            r[static_cast<size_t>(i)] = {x, 2 / ((1 - x * x) * dp * dp)};
        }
        return r;
    }();
    return nw;
}

// The integral of g over every cell (sr-weighted: the result of g = 1 is the cell's solid angle).
template <class T, class G> void for_each_cell_integral(const SphereGrid& grid, G&& g, T zero, auto&& take) {
    const auto& gl = gauss_legendre16();
    for (int i = 0; i < grid.cos_bins; ++i) {
        const double c0 = -1 + 2.0 * i / grid.cos_bins, c1 = -1 + 2.0 * (i + 1) / grid.cos_bins;
        const double t0 = std::acos(c1), t1 = std::acos(c0);  // theta runs the other way
        for (int j = 0; j < grid.phi_bins; ++j) {
            const double p0 = 2 * kPiDouble * j / grid.phi_bins, p1 = 2 * kPiDouble * (j + 1) / grid.phi_bins;
            T sum = zero;
            for (const auto& a : gl) {
                const double t = t0 + (t1 - t0) * (a[0] + 1) / 2;
                const double st = std::sin(t), ct = std::cos(t);
                for (const auto& b : gl) {
                    const double p = p0 + (p1 - p0) * (b[0] + 1) / 2;
                    const Vec3 w(static_cast<float>(st * std::cos(p)), static_cast<float>(st * std::sin(p)),
                                 static_cast<float>(ct));
                    sum += g(w) * (a[1] * b[1] * st);
                }
            }
            take(i * grid.phi_bins + j, sum * ((t1 - t0) / 2 * (p1 - p0) / 2));
        }
    }
}

inline std::vector<double> integrate_cells(const SphereGrid& grid, const std::function<double(Vec3)>& g) {
    std::vector<double> out(static_cast<size_t>(grid.cells()));
    for_each_cell_integral(grid, g, 0.0, [&](int cell, double v) { out[static_cast<size_t>(cell)] = v; });
    return out;
}

// The integral over the whole sphere of an RGB function (in double).
inline std::array<double, 3> integrate_sphere(const SphereGrid& grid, const std::function<Vec3(Vec3)>& g) {
    struct D3 {
        double v[3];
        D3& operator+=(const D3& o) { for (int i = 0; i < 3; ++i) v[i] += o.v[i]; return *this; }
        D3 operator*(double s) const { return {{v[0] * s, v[1] * s, v[2] * s}}; }
    };
    std::array<double, 3> out{0, 0, 0};
    for_each_cell_integral(
        grid, [&](Vec3 w) { const Vec3 x = g(w); return D3{{x.x, x.y, x.z}}; }, D3{{0, 0, 0}},
        [&](int, D3 v) { for (int i = 0; i < 3; ++i) out[static_cast<size_t>(i)] += v.v[i]; });
    return out;
}

}  // namespace sl::test
