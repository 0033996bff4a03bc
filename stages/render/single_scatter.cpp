#include "stages/render/single_scatter.h"

#include <algorithm>
#include <cmath>

#include "core/pass_sequences.h"
#include "foundation/constants.h"

namespace sl {
namespace {

constexpr double kInvC = 1.0 / kSpeedOfLight;
constexpr double kGolden = 0.6180339887498949;  // strata's uniforms: u + k phi (mod 1)
constexpr double kGolden2 = 0.7548776662466927;  // a quad's point: u4 + k phi2, u5 + k phi3
constexpr double kGolden3 = 0.5698402909980532;
// The closest a camera line is taken to pass by a light's point: a line through it would see
// an infinite integral (1/h); below 0.1 mm the pixel's average is dominated by the rest of it.
constexpr double kMinPassBy = 1e-4;

// The arrival time T(t) of one light sample's light scattered at distance t along the segment,
// and its inverse on a piece where it is monotone. A point at L: T = T0 + (|L - x(t)| + k t)/c
// with k = 1 under camera_tof (non-decreasing in t), k = 0 otherwise (decreasing up to the
// projection tc of L, then increasing). A sun: linear in t.
struct ArrivalCurve {
    bool point = true;
    double t0 = 0;      // ns: point, T without the distance terms; sun, T(0)
    double tc = 0, h = kMinPassBy;  // point: L's projection on the line and distance from it
    double k = 0;       // 1 with camera_tof
    double slope = 0;   // sun: dT/dt, ns/m

    double at(double t) const {
        if (!point) return t0 + slope * t;
        const double u = t - tc;
        return t0 + (std::sqrt(h * h + u * u) + k * t) * kInvC;
    }
    // The t on the piece `side` (-1: t <= tc, +1: t >= tc, 0: the only piece) where T(t) = tau.
    double inverse(double tau, int side) const {
        if (!point) return (tau - t0) / slope;
        const double D = (tau - t0) * kSpeedOfLight;
        if (k == 0) {
            const double q = D * D - h * h;
            return tc + side * (q > 0 ? std::sqrt(q) : 0.0);
        }
        const double E = D - tc;  // sqrt(h^2 + u^2) + u = E, u = t - tc
        if (!(E > 0)) return -INFINITY;
        return tc + (E * E - h * h) / (2 * E);
    }
};

struct Piece {
    double a, b;  // distances along the segment
    int side;
};

}  // namespace

void single_scatter_along(const RenderContext& ctx, const CameraSegment& sg, Rng& rng, SectionBuffer& buffer,
                          DepositQueue& deposits, size_t pixel, SingleScatterCounters& counters) {
    const HomogeneousMedium& medium = *ctx.medium;
    const Timeline& tl = ctx.timeline;
    const BucketFinder bucket(tl);
    const SectionLayout& layout = buffer.layout;
    const bool tof = ctx.render.camera_tof;
    const double S = sg.length;
    // The whole timeline's buckets (those of one section holding every frame): the strata do
    // not depend on the section.
    const int64_t j_lo = 1 - tl.pulse_buckets, j_end = tl.frames;
    const Vec3 sigma_s = medium.sigma_s();
    float sigma_min = INFINITY;  // the clearest channel that interacts: the sun's distance pdf
    for (int c = 0; c < 3; ++c)
        if (medium.sigma_t()[c] > 0) sigma_min = std::min(sigma_min, medium.sigma_t()[c]);
    const double back_ns = tof ? sg.camera_ns : 0.0;
    const Vec3 o = sg.origin, d = sg.dir;
    // A pulse's frames are one pulse width of buckets each: a quad's light is then taken from one
    // point of its area per segment, whose arrival times are the strata's own (docs/medium.md).
    const bool quad_by_area = ctx.pulse_quads_by_area && ctx.emission == EmissionMode::Pulse;

    for (size_t i = 0; i < ctx.lights.count(); ++i) {
        // The light sample (u1, u2) and the distances' uniform (u3), stratified over the passes
        // along the pixel's first segment: in a shaft, where each distance sample is lit or not,
        // independent ones leave the lit share a binomial count (the cathedral's first lit frame:
        // 40.5 % noise, 32.7 % stratified). Drawn even when replaced: 5 uniforms per light always.
        float u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
        const float u4 = rng.uniform(), u5 = rng.uniform();
        if (sg.stratified_pixel >= 0)
            halton_pass_point(ctx.render.seed, 13, i, static_cast<uint64_t>(sg.stratified_pixel), sg.pass, u1, u2, &u3);
        if (!(S > 0)) continue;
        InScatterLight ls;
        if (!ctx.lights.sample_in_medium(i, u1, u2, ls, quad_by_area)) continue;
        ArrivalCurve curve;
        curve.k = tof ? 1 : 0;
        Piece pieces[2];
        int npieces = 0;
        double lambda = 0;  // the sun's truncated exponential rate (0: uniform)
        if (ls.point_like()) {
            const double vx = double(ls.position.x) - o.x, vy = double(ls.position.y) - o.y,
                         vz = double(ls.position.z) - o.z;
            curve.tc = vx * d.x + vy * d.y + vz * d.z;
            const double px = vx - curve.tc * d.x, py = vy - curve.tc * d.y, pz = vz - curve.tc * d.z;
            curve.h = std::max(kMinPassBy, std::sqrt(px * px + py * py + pz * pz));
            curve.t0 = ls.start_ns + back_ns;
            if (tof) {
                pieces[npieces++] = {0, S, 0};
            } else {
                const double m = std::clamp(curve.tc, 0.0, S);
                if (m > 0) pieces[npieces++] = {0, m, -1};
                if (m < S) pieces[npieces++] = {m, S, +1};
            }
        } else {
            curve.point = false;
            const double per_m = static_cast<double>(dot(d, ls.axis)) / ls.sun_cos;  // shadow length's rate
            curve.t0 = (static_cast<double>(dot(o, ls.axis)) - ls.sun_h0) / ls.sun_cos * kInvC + back_ns;
            curve.slope = (per_m + curve.k) * kInvC;
            pieces[npieces++] = {0, S, 0};
            // The camera leg's and the shadow ray's transmittance fall as e^(-sigma (1 + per_m) t)
            // (the shadow ray taken inside the medium all along): sampled in the clearest channel.
            if (std::isfinite(sigma_min)) lambda = sigma_min * (1 + per_m);
        }

        for (int pc = 0; pc < npieces; ++pc) {
            const Piece& pz = pieces[pc];
            const double Ta = curve.at(pz.a), Tb = curve.at(pz.b);
            const bool increasing = Tb >= Ta;
            const double lo_T = std::min(Ta, Tb), hi_T = std::max(Ta, Tb);
            // Strata: -1 before the timeline's first bucket, then groups of g buckets, then
            // n_groups for everything at or after the end.
            const int64_t jb_lo = std::clamp<int64_t>(bucket(lo_T), j_lo - 1, j_end);
            const int64_t jb_hi = std::clamp<int64_t>(bucket(hi_T), j_lo - 1, j_end);
            const int64_t touched = jb_hi - jb_lo + 1;
            const int64_t g = std::max<int64_t>(1, (touched + kMaxStrata - 1) / kMaxStrata);
            const int64_t n_groups = (j_end - j_lo + g - 1) / g;
            auto stratum_of = [&](int64_t j) -> int64_t {
                if (j < j_lo) return -1;
                if (j >= j_end) return n_groups;
                return (j - j_lo) / g;
            };
            const bool flat = !(hi_T - lo_T > 1e-12 * (1 + std::abs(hi_T)));
            auto distance_at = [&](double tau) {
                if (tau <= lo_T) return increasing ? pz.a : pz.b;
                if (tau >= hi_T) return increasing ? pz.b : pz.a;
                return std::clamp(curve.inverse(tau, pz.side), pz.a, pz.b);
            };
            const int64_t k_first = stratum_of(jb_lo), k_last = stratum_of(jb_hi);
            for (int64_t k = k_first; k <= k_last; ++k) {
                // The stratum's buckets [jk0, jk1) and times [tau0, tau1).
                const int64_t jk0 = k < 0 ? j_lo - 1 : (k == n_groups ? j_end : j_lo + k * g);
                const int64_t jk1 = k < 0 ? j_lo : (k == n_groups ? j_end + 1 : std::min(j_lo + (k + 1) * g, j_end));
                int slot = -1;
                if (jk1 - jk0 == 1 && !ls.rect) {  // one bucket (or before/after): its slot, known before sampling
                    slot = layout.slot_of_bucket(jk0);
                    if (slot < 0) continue;
                }
                double ta = pz.a, tb = pz.b;
                if (!flat) {
                    const double tau0 = k < 0 ? -INFINITY : tl.edge(jk0);
                    const double tau1 = k == n_groups ? INFINITY : tl.edge(jk1);
                    ta = distance_at(tau0);
                    tb = distance_at(tau1);
                    if (ta > tb) std::swap(ta, tb);
                }
                if (!(tb > ta)) continue;
                double u = u3 + kGolden * static_cast<double>(k + 2) + (pz.side > 0 ? 0.5 : 0.0);
                u -= std::floor(u);
                // A distance in [ta, tb] and its density there.
                double t, pdf;
                const double len = tb - ta;
                if (curve.point) {
                    const double h = curve.h;
                    const double th_a = std::atan2(ta - curve.tc, h), th_b = std::atan2(tb - curve.tc, h);
                    if (th_b - th_a > 1e-9) {  // equiangular about the light's point
                        t = std::clamp(curve.tc + h * std::tan(th_a + u * (th_b - th_a)), ta, tb);
                        const double w = t - curve.tc;
                        pdf = h / ((th_b - th_a) * (h * h + w * w));
                    } else {
                        t = ta + u * len;
                        pdf = 1 / len;
                    }
                } else if (std::abs(lambda * len) > 1e-4) {  // truncated exponential
                    const double mass = -std::expm1(-lambda * len);
                    const double s = -std::log1p(-u * mass) / lambda;
                    t = std::clamp(ta + s, ta, tb);
                    pdf = lambda * std::exp(-lambda * (t - ta)) / mass;
                } else {
                    t = ta + u * len;
                    pdf = 1 / len;
                }
                if (!(pdf > 0) || !std::isfinite(pdf)) continue;
                const Vec3 x = o + d * static_cast<float>(t);
                Vec3 e, to_light;
                float dist = 0;
                if (ls.rect) {
                    // A fresh point of the quad, by solid angle: its light arrives at its own time,
                    // within the quad's size over c of the stratum's.
                    // (two more uniforms, independent of the distance's)
                    double a = u4 + kGolden2 * static_cast<double>(k + 2) + (pz.side > 0 ? 0.5 : 0.0);
                    double b = u5 + kGolden3 * static_cast<double>(k + 2) + (pz.side > 0 ? 0.5 : 0.0);
                    a -= std::floor(a);
                    b -= std::floor(b);
                    if (!ls.at_rect(x, static_cast<float>(a), static_cast<float>(b), e, to_light, dist)) continue;
                    const double at = ls.start_ns + dist * kInvC + back_ns + (tof ? t * kInvC : 0.0);
                    slot = layout.slot_of_bucket(bucket(at));
                    if (slot < 0) continue;
                } else {
                    if (slot < 0) {  // a group of buckets: the bucket of the sample's own time, kept inside the group
                        const int64_t j = std::clamp<int64_t>(bucket(curve.at(t)), jk0, jk1 - 1);
                        slot = layout.slot_of_bucket(j);
                        if (slot < 0) continue;
                    }
                    if (!ls.at(x, e, to_light, dist)) continue;
                }
                ++counters.samples;
                const float phase = medium.phase(dot(to_light, d));  // light along -to_light, leaving along -d
                Vec3 L = sg.beta * sigma_s * medium.transmittance(static_cast<float>(t)) * e *
                         static_cast<float>(phase / pdf);
                if (is_black(L) || !is_finite(L)) continue;
                ++counters.shadow_rays;
                if (ctx.geometry.occluded(x, to_light, 0, dist * (1 - 1e-4f))) continue;
                L *= medium.transmittance(x, to_light, dist);
                deposits.add(buffer.slot(pixel, slot), L.x, L.y, L.z);
            }
        }
    }
}

}  // namespace sl
