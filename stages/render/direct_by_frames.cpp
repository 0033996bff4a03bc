#include "stages/render/direct_by_frames.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/parallelogram_band.h"
#include "core/pass_sequences.h"
#include "core/rng.h"
#include "foundation/constants.h"

namespace sl {
namespace {

// Each band's pair of uniforms is the pixel's pair shifted modulo 1 by two numbers hashed from
// the band's earliest time (the exact double): a timeline shifted by whole frames, whose edges
// are the same numbers, draws the same point for the same band (TimeEdges.*), and each band's
// points stay stratified over the passes (the shift is the same in every pass).
struct BandShift {
    float a, b;
    explicit BandShift(double edge_ns) {
        uint64_t bits;
        std::memcpy(&bits, &edge_ns, sizeof bits);
        const uint64_t h = mix64(bits ^ 0x9e3779b97f4a7c15ull);
        a = static_cast<float>(h >> 40) * 0x1p-24f;
        b = static_cast<float>((h >> 16) & 0xffffff) * 0x1p-24f;
    }
};

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
    // The bands are the cells of the timeline's lattice of edges, start + j delta, also before
    // the start and after the end (where the section's slot for them is the before or after
    // one): a band is the same interval of time whatever the timeline, when the edges are.
    const double t_near = quad.min_distance() / kSpeedOfLight + back_ns;
    const double t_far = quad.max_distance() / kSpeedOfLight + back_ns;
    // One bucket: the one sample of the whole quad does (and costs less). A spread wider than
    // kMaxFrameBands frames: too, judged by the frame width, not by the buckets this timeline
    // has there, so that shifted timelines decide alike.
    if ((t_far - t_near) > kMaxFrameBands * tl.delta()) return false;
    const int64_t jb_lo = bucket(t_near), jb_hi = bucket(t_far);
    if (!(jb_hi > jb_lo) || jb_hi - jb_lo > kMaxFrameBands + 2) return false;  // the last: far off the timeline
    const Vec3 radiance = ctx.lights.quad_radiance(light);
    const SectionLayout& layout = buffer.layout;
    for (int64_t j = jb_lo; j <= jb_hi; ++j) {
        const int slot = layout.slot_of_bucket(j);
        if (slot < 0) continue;  // a bucket this section keeps nothing for: no shadow ray either
        // The band of distances whose light arrives in bucket j.
        const double edge0 = tl.edge(j), edge1 = tl.edge(j + 1);
        const double d0 = (edge0 - back_ns) * kSpeedOfLight, d1 = (edge1 - back_ns) * kSpeedOfLight;
        Vec3 y;
        double w;
        const BandShift shift(edge0);
        if (!quad.sample_band(d0, d1, add_mod1(u1, shift.a), add_mod1(u2, shift.b), y, w)) continue;
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
        if (ctx.geometry.occluded_to(origin, y)) continue;
        if (ctx.medium) e *= ctx.medium->transmittance(origin, wi, d);
        const Vec3 L = f * e;
        deposits.add(buffer.slot(pixel, slot), L.x, L.y, L.z);
    }
    return true;
}

}  // namespace sl
