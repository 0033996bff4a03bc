#pragma once
// Scenes and reference integrals for the participating-medium tests.
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "foundation/constants.h"
#include "config/scene_desc.h"
#include "core/camera.h"

namespace sl::test {

inline LightDesc point_light(Vec3 at, float power) {
    LightDesc l;
    l.type = LightType::Point;
    l.position = at;
    l.power = Vec3(power);
    return l;
}

constexpr double kC = 0.299792458;  // m/ns

// No surfaces at all: one light in a medium box of half-size `half` around the origin, and a
// camera; max_depth 1 (single scattering only).
inline SceneDesc light_in_open_medium(const LightDesc& light, Vec3 sigma_a, Vec3 sigma_s, float g, float half,
                                      Vec3 cam_pos, Vec3 look_at, float vfov, int res) {
    SceneDesc s;
    s.source = "<test open medium>";
    s.camera.position = cam_pos;
    s.camera.look_at = look_at;
    s.camera.up = {0, 1, 0};
    s.camera.vfov_deg = vfov;
    s.camera.width = s.camera.height = res;
    MaterialDesc m;
    m.name = "black";
    m.albedo = Vec3(0);
    s.materials.push_back(m);
    s.lights.push_back(light);
    s.medium.present = true;
    s.medium.sigma_a = sigma_a;
    s.medium.sigma_s = sigma_s;
    s.medium.g = g;
    s.medium.has_bounds = true;
    s.medium.bounds_min = Vec3(-half);
    s.medium.bounds_max = Vec3(half);
    s.render.max_depth = 1;
    return s;
}

// Single scattering seen along the ray o + s d inside a medium box, from a light at L with
// intensity I(unit direction from the light) per channel: for each frame end T in `ends`,
//   integral over s of e^(-st s) ss p(cos) I e^(-st r) / r^2,  restricted to arrival < T,
// arrival = r / c (+ s / c with camera_tof). Composite Simpson on a fine grid between the
// points where the integrand switches on or off (found by bisection).
struct SingleScatterRef {
    Vec3 light;
    Vec3 sigma_t, sigma_s;
    float g = 0;
    Vec3 lo, hi;  // medium box
    bool tof = false;
    bool always_lit = true;  // false for a spot: find where its cone begins and ends
    std::function<Vec3(Vec3)> intensity;

    double phase(double cos_t) const {
        double d = 1 + g * g - 2 * g * cos_t;
        return (1 - g * g) / (4 * sl::kPiDouble * d * std::sqrt(d));
    }
    double exit_distance(Vec3 o, Vec3 d) const {
        double t1 = 1e30;
        for (int a = 0; a < 3; ++a) {
            if (d[a] == 0) continue;
            double ta = ((d[a] > 0 ? hi[a] : lo[a]) - o[a]) / d[a];
            t1 = std::min(t1, ta);
        }
        return t1;
    }
    // Adds the integrals for every T in `ends` to out[k] (per channel).
    void add(Vec3 o, Vec3 d, const std::vector<double>& ends, std::vector<Vec3>& out) const {
        const double smax = exit_distance(o, d);
        auto arrival = [&](double s) {
            Vec3 x = o + d * static_cast<float>(s);
            double r = length(x - light);
            return (r + (tof ? s : 0.0)) / kC;
        };
        auto lit = [&](double s) {  // inside the light's emission (a spot's cone)
            Vec3 x = o + d * static_cast<float>(s);
            return !is_black(intensity(normalize(x - light)));
        };
        auto f = [&](double s) {
            Vec3 x = o + d * static_cast<float>(s);
            Vec3 v = x - light;
            double r2 = dot(v, v), r = std::sqrt(r2);
            Vec3 w = v / static_cast<float>(r);
            Vec3 I = intensity(w);
            double p = phase(-dot(w, d));  // light travels along w, leaves towards the camera (-d)
            Vec3 res;
            for (int c = 0; c < 3; ++c)
                res[c] = static_cast<float>(std::exp(-sigma_t[c] * (s + r)) * sigma_s[c] * p * I[c] / r2);
            return res;
        };
        // Breakpoints: where `lit` changes on a coarse grid (spots), refined by bisection.
        std::vector<double> br{0.0, smax};
        if (!always_lit) {
            const int coarse = 4000;
            for (int i = 0; i < coarse; ++i) {
                double a = smax * i / coarse, b = smax * (i + 1) / coarse;
                bool la = lit(a);
                if (la == lit(b)) continue;
                for (int it = 0; it < 60; ++it) {
                    double m = 0.5 * (a + b);
                    (lit(m) == la ? a : b) = m;
                }
                br.push_back(0.5 * (a + b));
            }
        }
        const Vec3 lo_v = light - o;
        const double q = dot(lo_v, lo_v), sc = dot(lo_v, d);
        for (size_t k = 0; k < ends.size(); ++k) {
            const double D = kC * ends[k];
            auto before = [&](double s) { return arrival(s) < ends[k]; };
            // Where the arrival time crosses T, in closed form.
            std::vector<double> pts = br;
            if (!tof && D * D > q - sc * sc) {
                double h = std::sqrt(D * D - (q - sc * sc));
                for (double x : {sc - h, sc + h}) if (x > 0 && x < smax) pts.push_back(x);
            }
            if (tof && D > std::sqrt(q)) {
                double x = (D * D - q) / (2 * (D - sc));
                if (x > 0 && x < smax) pts.push_back(x);
            }
            std::sort(pts.begin(), pts.end());
            for (size_t j = 0; j + 1 < pts.size(); ++j) {
                double a = pts[j], b = pts[j + 1];
                if (!(b > a)) continue;
                double mid = 0.5 * (a + b);
                if (!before(mid) || !lit(mid)) continue;
                const int n = 256;  // Simpson panels
                double h = (b - a) / n;
                double acc[3] = {0, 0, 0};
                for (int i = 0; i <= n; ++i) {
                    double wgt = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
                    Vec3 v = f(a + i * h);
                    for (int c = 0; c < 3; ++c) acc[c] += wgt * v[c];
                }
                for (int c = 0; c < 3; ++c) out[k][c] += static_cast<float>(acc[c] * h / 3);
            }
        }
    }
};

}  // namespace sl::test
