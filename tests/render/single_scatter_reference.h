#pragma once
// An independent quadrature of single scattering for the tests of the camera pass's next-event
// estimate: along each camera ray (unfolded through perfect mirrors, planes z = const), at many
// midpoints, sigma_s p(cos) E(x) e^(-sigma_t (camera leg + shadow length)), binned by the arrival
// time into the timeline's buckets and assembled into frames as the renderer does (constant
// emission: everything before the frame's end; a pulse of m buckets: the m ending there).
// Lights are given as a callback that lists, for a point x, each contribution's irradiance on a
// plane facing it, the unit direction towards it, the time its light left and the length of its
// shadow ray inside the medium: a point, a spot, a quad (a grid of points) or a sun.
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "config/scene_desc.h"
#include "core/camera.h"
#include "foundation/constants.h"
#include "foundation/timeline.h"

namespace sl::test {

struct LightContribution {
    Vec3 irradiance;   // W/m^2 on a plane facing the light
    Vec3 to_light;     // unit
    double light_ns;   // when the light reaching x left its source, plus its flight to x
    double shadow_len;  // inside the medium
};
using LightModel = std::function<void(Vec3 x, const std::function<void(const LightContribution&)>&)>;

// Length of o + t d inside the box [lo, hi] from t = 0 (o inside), to its exit.
inline double box_exit(Vec3 o, Vec3 d, Vec3 lo, Vec3 hi) {
    double t1 = 1e30;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0) continue;
        t1 = std::min(t1, (static_cast<double>(d[a] > 0 ? hi[a] : lo[a]) - o[a]) / d[a]);
    }
    return std::max(0.0, t1);
}

struct QuadratureSetup {
    Vec3 sigma_t, sigma_s;
    float g = 0;
    Vec3 lo, hi;          // the medium's box (the camera inside it)
    bool tof = false;
    std::vector<float> mirror_z;  // perfect mirrors filling the planes z = c (unfolded), in any order
    int max_segments = 1;         // segments followed through the mirrors
    int steps = 3000;             // midpoints per segment
    int sub = 2;                  // sub x sub rays per pixel
    float from_z = -1e30f;        // only the points with z >= from_z scatter (beyond a pane)
};

// The quadrature's medium and timing, as a scene states them.
inline QuadratureSetup quadrature_setup(const SceneDesc& s) {
    QuadratureSetup q;
    q.sigma_t = s.medium.sigma_a + s.medium.sigma_s;
    q.sigma_s = s.medium.sigma_s;
    q.g = s.medium.g;
    q.lo = s.medium.bounds_min;
    q.hi = s.medium.bounds_max;
    q.tof = s.render.camera_tof;
    return q;
}

// Per pixel, per bucket j in [j_lo, frames) (index j - j_lo), plus the after-slot at the end.
inline std::vector<std::vector<Vec3>> single_scatter_buckets(const SceneDesc& s, const Timeline& tl,
                                                             const QuadratureSetup& q, const LightModel& light) {
    PinholeCamera cam(s.camera);
    const int64_t j_lo = 1 - tl.pulse_buckets;
    const size_t nb = static_cast<size_t>(tl.frames - j_lo) + 1;
    const int w = s.camera.width, h = s.camera.height;
    std::vector<std::vector<Vec3>> out(static_cast<size_t>(w) * h, std::vector<Vec3>(nb));
    const double c = 0.299792458;
    auto phase = [&](double cos_t) {
        double dd = 1 + q.g * q.g - 2 * q.g * cos_t;
        return (1 - q.g * q.g) / (4 * kPiDouble * dd * std::sqrt(dd));
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::vector<Vec3>& px = out[static_cast<size_t>(y) * w + x];
            for (int sj = 0; sj < q.sub; ++sj)
                for (int si = 0; si < q.sub; ++si) {
                    Vec3 o = cam.position();
                    Vec3 d = cam.direction(x + (si + 0.5f) / q.sub, y + (sj + 0.5f) / q.sub);
                    double leg = 0;  // camera leg so far (all inside the medium)
                    const float wgt = 1.0f / static_cast<float>(q.sub * q.sub);
                    for (int seg = 0; seg < q.max_segments; ++seg) {
                        double len = box_exit(o, d, q.lo, q.hi);
                        float hit_z = 0;
                        bool bounce = false;
                        for (float mz : q.mirror_z) {
                            if (d.z == 0) continue;
                            double t = (mz - o.z) / d.z;
                            if (t > 1e-5 && t < len) { len = t; hit_z = mz; bounce = true; }
                        }
                        const double dt = len / q.steps;
                        for (int i = 0; i < q.steps; ++i) {
                            const double t = (i + 0.5) * dt;
                            const Vec3 p = o + d * static_cast<float>(t);
                            if (p.z < q.from_z) continue;
                            light(p, [&](const LightContribution& lc) {
                                const double ph = phase(dot(lc.to_light, d));
                                const double arrive = lc.light_ns + (q.tof ? (leg + t) / c : 0.0);
                                const int64_t j = std::clamp<int64_t>(tl.bucket(arrive), j_lo, tl.frames);
                                Vec3& acc = px[static_cast<size_t>(j - j_lo)];
                                for (int ch = 0; ch < 3; ++ch)
                                    acc[ch] += static_cast<float>(wgt * dt * q.sigma_s[ch] * ph * lc.irradiance[ch] *
                                                                  std::exp(-q.sigma_t[ch] * (leg + t + lc.shadow_len)));
                            });
                        }
                        if (!bounce) break;
                        o = o + d * static_cast<float>(len);
                        o.z = hit_z;
                        d.z = -d.z;
                        leg += len;
                    }
                }
        }
    return out;
}

// Frames from buckets, as the renderer assembles them (buckets before j_lo count as before
// the first: the quadrature clamps them into j_lo).
inline std::vector<std::vector<Vec3>> frames_of(const std::vector<std::vector<Vec3>>& buckets, const Timeline& tl,
                                                EmissionMode mode) {
    const int64_t j_lo = 1 - tl.pulse_buckets;
    std::vector<std::vector<Vec3>> f(buckets.size(), std::vector<Vec3>(static_cast<size_t>(tl.frames)));
    for (size_t p = 0; p < buckets.size(); ++p) {
        Vec3 run;
        for (int64_t j = j_lo; j < tl.frames; ++j) {
            run = run + buckets[p][static_cast<size_t>(j - j_lo)];
            if (j < 0) continue;
            if (mode == EmissionMode::Constant) {
                f[p][static_cast<size_t>(j)] = run;
            } else {
                Vec3 sum;
                for (int64_t b = j - tl.pulse_buckets + 1; b <= j; ++b) sum = sum + buckets[p][static_cast<size_t>(b - j_lo)];
                f[p][static_cast<size_t>(j)] = sum;
            }
        }
    }
    return f;
}

// Lights for the quadrature, in an open medium box (shadow rays entirely inside it).
inline LightModel point_model(Vec3 at, std::function<Vec3(Vec3 from_light)> intensity) {
    return [=](Vec3 x, const std::function<void(const LightContribution&)>& add) {
        const Vec3 v = at - x;
        const double r = length(v);
        if (!(r > 0)) return;
        const Vec3 wl = v / static_cast<float>(r);
        const Vec3 I = intensity(-wl);
        if (is_black(I)) return;
        add({I * static_cast<float>(1 / (r * r)), wl, r / 0.299792458, r});
    };
}

}  // namespace sl::test
