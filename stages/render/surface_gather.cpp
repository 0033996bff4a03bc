#include "stages/render/surface_gather.h"

#include <algorithm>

#include "core/glossy_path.h"
#include "core/sampling.h"
#include "stages/render/edge_radius.h"
#include "stages/render/gather_blockers.h"

namespace sl {

namespace {

// The gather. adder(k) (k: the pass's normalisation, 1 / (area x photons emitted)) returns
// add(slot, photon), which adds one photon's share to a slot of the pixel.
template <class Adder>
uint32_t gather_with(const RenderContext& ctx, const VisiblePoint& vp, const PhotonMap& photons,
                     int64_t photons_emitted, size_t pixel, SectionBuffer& buffer, Adder&& adder) {
    const BucketFinder bucket(ctx.timeline);  // every photon found asks it
    const SectionLayout& layout = buffer.layout;
    // Normals closer than ~45 degrees count as the same surface: keeps corners from leaking.
    constexpr float kSameSurface = 0.7f;
    const double inv_count = 1.0 / static_cast<double>(std::max<int64_t>(photons_emitted, 1));
    double& r2 = buffer.radius2[pixel];
    const Vec3 n = vp.normal;
    Vec3 p = vp.position;  // the disc's centre
    // Beside an edge of the surface the pixel's centre sees, the disc is cut at the edge's line
    // (edge_radius.h) when this point lies on that surface, before the line; else it gathers
    // in the disc shrunk to the edge's distance (the pixel's radius times the cut's `shrunk`).
    // A pixel has a cut, a star or neither.
    const size_t global = buffer.share.global(pixel);
    const EdgeCut* cut = ctx.gather_radii().cut(global);
    GatherBlockers::EdgeLine line{};
    bool use_cut = false;
    double gather_r2 = r2;
    // Or by its star (edge_radius.h), for a point on the surface the pixel's centre sees: the
    // disc round that centre, kept sector by sector where the surface is; a wall rising in it
    // sends the point to the shrunk disc too (below).
    const EdgeStar* star = ctx.gather_radii().star(global);
    const float shrunk = star ? star->shrunk : 1.0f;
    Vec3 star_t, star_b;
    if (star) {
        const Vec3 sn = decode_normal(star->normal);
        const float slack = 0.1f * static_cast<float>(std::sqrt(r2));
        if (ctx.edge_cuts && ctx.edge_stars && dot(sn, n) >= kSameSurface &&
            std::abs(dot(sn, p - star->centre)) <= slack) {
            p = star->centre;
            make_basis(sn, star_t, star_b);
        } else {
            star = nullptr;
            gather_r2 = r2 * static_cast<double>(shrunk) * shrunk;
        }
    }
    if (cut) {
        const Vec3 cn = decode_normal(cut->normal);
        line = {decode_normal(cut->across), cut->offset};
        const float slack = 0.1f * static_cast<float>(std::sqrt(r2));
        use_cut = ctx.edge_cuts && dot(cn, n) >= kSameSurface && std::abs(dot(cn, p) - cut->plane) <= slack &&
                  dot(line.across, p) < line.offset;
        if (!use_cut) gather_r2 = r2 * static_cast<double>(cut->shrunk) * cut->shrunk;
    }
    // The surfaces that cut the disc (a wall at a floor's edge): photons beyond them are not
    // gathered, and the disc's area is what is left of it (gather_blockers.h).
    GatherBlockers blockers(ctx.geometry, p, n, static_cast<float>(gather_r2), use_cut ? &line : nullptr);
    if (star && blockers.any()) {
        p = vp.position;
        gather_r2 = r2 * static_cast<double>(shrunk) * shrunk;
        star = nullptr;
        blockers = GatherBlockers(ctx.geometry, p, n, static_cast<float>(gather_r2));
    }
    // This pass's estimate: f * flux / (area * photons emitted this pass), area pi R^2 but for
    // blockers, or the star's.
    const double area = star ? star->area(std::sqrt(r2)) : blockers.area();
    const float k = static_cast<float>(inv_count / area);
    const float star_r = static_cast<float>(std::sqrt(r2));
    auto add = adder(k);
    // Sides: a photon counts only on the side of its own surface the point is on, and only if it
    // is not below the point's surface (stacked sheets, a thin table over a floor). The slack
    // (a tenth of the radius) lets curved surfaces of curvature radius above ~5 R through.
    const float slack = 0.1f * static_cast<float>(std::sqrt(gather_r2));
    uint32_t found = 0;
    photons.for_each_near(p.x, p.y, p.z, static_cast<float>(gather_r2), [&](const PhotonRecord& ph) {
        // cos(angle) < kSameSurface, without normalising the decoded normal.
        const Vec3 pn = decode_normal_unnormalized(ph.normal);
        const float c = dot(pn, n);
        if (c <= 0 || c * c < kSameSurface * kSameSurface * dot(pn, pn)) return;
        if (ph.depth > vp.depth_left) return;
        const Vec3 q{ph.x, ph.y, ph.z};
        const Vec3 v = q - p;
        if (dot(v, n) < -slack) return;  // below the point's surface
        const float behind = dot(v, pn);  // the point is behind the photon's surface
        if (behind > 0 && behind * behind > slack * slack * dot(pn, pn)) return;
        if (!blockers.visible(q)) return;
        if (star && !star->keeps(dot(v, star_t), dot(v, star_b), star_r)) return;
        ++found;
        const int s = layout.slot_of_bucket(bucket(ph.t_ns + vp.camera_ns));
        if (s < 0) return;
        add(s, ph);
    });
    if (found > 0) {
        const float alpha = ctx.render.alpha;
        const double count = buffer.photon_count[pixel];
        const float m = static_cast<float>(found) * vp.share;  // = found, exactly as before, unsplit
        const double count_new = count + alpha * m;
        r2 *= count_new / (count + m);
        buffer.photon_count[pixel] = count_new;
    }
    return found;
}

}  // namespace

uint32_t gather_surface_at(const RenderContext& ctx, const VisiblePoint& vp, const PhotonMap& photons,
                           int64_t photons_emitted, size_t pixel, SectionBuffer& buffer,
                           DepositQueue& deposits) {
    if (!vp.glossy) {  // Lambertian: the BRDF is in the weight already
        return gather_with(ctx, vp, photons, photons_emitted, pixel, buffer, [&](float k) {
            const float wr = vp.weight.x * k, wg = vp.weight.y * k, wb = vp.weight.z * k;
            return [&, wr, wg, wb](int s, const PhotonRecord& ph) {
                deposits.add(buffer.slot(pixel, s), wr * ph.r, wg * ph.g, wb * ph.b);
            };
        });
    }
    // GGX: f(wo, wi) for each photon's incoming direction, in the point's shading frame.
    const LocalFrame frame(vp.bsdf_normal);
    const Vec3 wo = frame.local(vp.wo);
    return gather_with(ctx, vp, photons, photons_emitted, pixel, buffer, [&](float k) {
        const Vec3 w = vp.weight * k;
        return [&, w](int s, const PhotonRecord& ph) {
            const Vec3 f = bsdf::eval(vp.bsdf, wo, frame.local(decode_normal(ph.incoming))) * w;
            deposits.add(buffer.slot(pixel, s), f.x * ph.r, f.y * ph.g, f.z * ph.b);
        };
    });
}

}  // namespace sl
