#include "stages/render/direct_by_frames.h"

#include <algorithm>
#include <cmath>

#include "core/parallelogram_band.h"
#include "foundation/constants.h"

namespace sl {
namespace {

constexpr double kGolden2 = 0.7548776662466927;  // each band's pair: u1 + j phi2, u2 + j phi3 (mod 1)
constexpr double kGolden3 = 0.5698402909980532;

float shifted(float u, double step, int64_t j) {
    double v = static_cast<double>(u) + step * static_cast<double>(j + 2);
    v -= std::floor(v);
    return std::min(static_cast<float>(v), 0x1.fffffep-1f);
}

}  // namespace

bool quad_direct_by_frames(const RenderContext& ctx, size_t light, Vec3 p, Vec3 origin, Vec3 nf, Vec3 ns, double back_ns,
                           float u1, float u2, Vec3 f, SectionBuffer& buffer, DepositQueue& deposits, size_t pixel,
                           uint64_t& rays) {
    Vec3 corner, e1, e2, normal;
    if (!ctx.lights.quad_geometry(light, corner, e1, e2, normal)) return false;
    const ParallelogramFromPoint quad(p, corner, e1, e2);
    if (!quad.valid()) return false;
    const Timeline& tl = ctx.timeline;
    const BucketFinder bucket(tl);
    // The whole timeline's buckets, and one stratum before them and one after (as in
    // single_scatter.cpp): the bands do not depend on the section.
    const int64_t j_lo = 1 - tl.pulse_buckets, j_end = tl.frames;
    const double t_near = quad.min_distance() / kSpeedOfLight + back_ns;
    const double t_far = quad.max_distance() / kSpeedOfLight + back_ns;
    const int64_t jb_lo = std::clamp<int64_t>(bucket(t_near), j_lo - 1, j_end);
    const int64_t jb_hi = std::clamp<int64_t>(bucket(t_far), j_lo - 1, j_end);
    if (jb_hi == jb_lo || jb_hi - jb_lo + 1 > kMaxFrameBands) return false;
    const Vec3 radiance = ctx.lights.quad_radiance(light);
    const SectionLayout& layout = buffer.layout;
    for (int64_t j = jb_lo; j <= jb_hi; ++j) {
        const int slot = layout.slot_of_bucket(j);
        if (slot < 0) continue;  // a bucket this section keeps nothing for: no shadow ray either
        // The band of distances whose light arrives in bucket j.
        const double d0 = j < j_lo ? 0.0 : (tl.edge(j) - back_ns) * kSpeedOfLight;
        const double d1 = j >= j_end ? INFINITY : (tl.edge(j + 1) - back_ns) * kSpeedOfLight;
        Vec3 y;
        double w;
        if (!quad.sample_band(d0, d1, shifted(u1, kGolden2, j), shifted(u2, kGolden3, j), y, w)) continue;
        const Vec3 v = y - p;
        const float d2 = dot(v, v);
        if (!(d2 > 0)) continue;
        const float d = std::sqrt(d2);
        const Vec3 wi = v / d;
        const float cos_p = dot(ns, wi), cos_l = -dot(normal, wi);
        if (cos_p <= 0 || cos_l <= 0 || dot(wi, nf) <= 0) continue;
        Vec3 e = radiance * static_cast<float>(cos_l * cos_p / d2 * w);
        if (is_black(e) || !is_finite(e)) continue;
        ++rays;
        if (ctx.geometry.occluded(origin, wi, 0, d * (1 - 1e-4f))) continue;
        if (ctx.medium) e *= ctx.medium->transmittance(origin, wi, d);
        const Vec3 L = f * e;
        deposits.add(buffer.slot(pixel, slot), L.x, L.y, L.z);
    }
    return true;
}

}  // namespace sl
