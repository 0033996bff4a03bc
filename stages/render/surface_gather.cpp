#include "stages/render/surface_gather.h"

#include <algorithm>

#include "core/glossy_path.h"
#include "core/sampling.h"
#include "stages/render/edge_radius.h"
#include "stages/render/gather_blockers.h"

namespace sl {

namespace {

// Normals closer than ~45 degrees count as the same surface: keeps corners from leaking.
constexpr float kSameSurface = GatherRadii::kSameSurface;

// Where and how a point gathers by the rule of one pixel (its cut, its star or neither), at
// that pixel's radius^2 r2 this pass.
struct GatherDisc {
    Vec3 centre;       // the disc's centre: the point, or the star's centre
    double r2 = 0;     // the pixel's radius^2 (a star's region is kept out to it)
    double gather_r2 = 0;
    double shrunk_r2 = 0;  // the disc shrunk to the edge's distance
    const EdgeStar* star = nullptr;
    Vec3 star_t, star_b;
    bool use_cut = false;
    GatherBlockers::EdgeLine line{};
    // False: the pixel has a cut or a star and the point is off its surface (or past the cut's
    // line): the disc is the shrunk one. Plain pixels: whether the point is on the plane their
    // centre sees, when the planes are kept (GatherRadii::plane).
    bool on_surface = true;
};

GatherDisc disc_of(const RenderContext& ctx, size_t global, Vec3 x, Vec3 n, double r2) {
    const GatherRadii& radii = ctx.gather_radii();
    GatherDisc d;
    d.centre = x;
    d.r2 = d.gather_r2 = d.shrunk_r2 = r2;
    const float slack = 0.1f * static_cast<float>(std::sqrt(r2));
    // Beside an edge of the surface the pixel's centre sees, the disc is cut at the edge's line
    // (edge_radius.h) when this point lies on that surface, before the line; else it gathers
    // in the disc shrunk to the edge's distance (the pixel's radius times the cut's `shrunk`).
    // A pixel has a cut, a star or neither.
    const EdgeCut* cut = radii.cut(global);
    // Or by its star (edge_radius.h), for a point on the surface the pixel's centre sees: the
    // disc round that centre, kept sector by sector where the surface is; a wall rising in it
    // sends the point to the shrunk disc too (gather_with).
    const EdgeStar* star = radii.star(global);
    if (star) {
        d.shrunk_r2 = r2 * static_cast<double>(star->shrunk) * star->shrunk;
        const Vec3 sn = decode_normal(star->normal);
        if (ctx.edge_cuts && ctx.edge_stars && dot(sn, n) >= kSameSurface && std::abs(dot(sn, x - star->centre)) <= slack) {
            d.centre = star->centre;
            d.star = star;
            make_basis(sn, d.star_t, d.star_b);
        } else {
            d.gather_r2 = d.shrunk_r2;
            d.on_surface = false;
        }
    }
    if (cut) {
        const Vec3 cn = decode_normal(cut->normal);
        d.line = {decode_normal(cut->across), cut->offset};
        d.use_cut = ctx.edge_cuts && dot(cn, n) >= kSameSurface && std::abs(dot(cn, x) - cut->plane) <= slack &&
                    dot(d.line.across, x) < d.line.offset;
        d.shrunk_r2 = r2 * static_cast<double>(cut->shrunk) * cut->shrunk;
        if (!d.use_cut) {
            d.gather_r2 = d.shrunk_r2;
            d.on_surface = false;
        }
    }
    if (!cut && !star && !radii.plane.empty()) d.on_surface = radii.plane[global].holds(x, n, slack);
    return d;
}

// The gather. adder(k) (k: the pass's normalisation, 1 / (area x photons emitted)) returns
// add(slot, photon), which adds one photon's share to a slot of the pixel.
template <class Adder>
uint32_t gather_with(const RenderContext& ctx, const VisiblePoint& vp, const PhotonMap& photons,
                     int64_t photons_emitted, size_t pixel, SectionBuffer& buffer, Adder&& adder) {
    const BucketFinder bucket(ctx.timeline);  // every photon found asks it
    const SectionLayout& layout = buffer.layout;
    const double inv_count = 1.0 / static_cast<double>(std::max<int64_t>(photons_emitted, 1));
    double& r2 = buffer.radius2[pixel];
    const Vec3 n = vp.normal;
    const GatherRadii& radii = ctx.gather_radii();
    const size_t global = buffer.share.global(pixel);
    // The disc of the point: by the rule of the pixel whose centre sees its surface (disc_of),
    // the pixel's own, or where the point lies off it (across a silhouette), the first
    // neighbour's whose centre sees the point's plane, at that neighbour's initial radius times
    // this pixel's shrink so far; failing both, the pixel's own shrunk disc.
    GatherDisc disc = disc_of(ctx, global, vp.position, n, r2);
    if (!disc.on_surface && ctx.edge_neighbours && !radii.radius.empty()) {
        const float slack = 0.1f * static_cast<float>(std::sqrt(r2));
        const int64_t q = radii.neighbour_on(global, ctx.width, vp.position, n, slack);
        if (q >= 0) {
            const double scale = static_cast<double>(radii.radius[static_cast<size_t>(q)]) / radii.radius[global];
            GatherDisc other = disc_of(ctx, static_cast<size_t>(q), vp.position, n, r2 * scale * scale);
            if (other.on_surface) disc = other;
        }
    }
    Vec3 p = disc.centre;
    double gather_r2 = disc.gather_r2;
    const EdgeStar* star = disc.star;
    const Vec3 star_t = disc.star_t, star_b = disc.star_b;
    // The surfaces that cut the disc (a wall at a floor's edge): photons beyond them are not
    // gathered, and the disc's area is what is left of it (gather_blockers.h).
    GatherBlockers blockers(ctx.geometry, p, n, static_cast<float>(gather_r2), disc.use_cut ? &disc.line : nullptr);
    if (star && blockers.any()) {
        p = vp.position;
        gather_r2 = disc.shrunk_r2;
        star = nullptr;
        blockers = GatherBlockers(ctx.geometry, p, n, static_cast<float>(gather_r2));
    }
    // This pass's estimate: f * flux / (area * photons emitted this pass), area pi R^2 but for
    // blockers, or the star's.
    const double area = star ? star->area(std::sqrt(disc.r2)) : blockers.area();
    const float k = static_cast<float>(inv_count / area);
    const float star_r = static_cast<float>(std::sqrt(disc.r2));
    auto add = adder(k);
    // Sides: a photon counts only on the side of its own surface the point is on, and only if it
    // is not below the point's surface (stacked sheets, a thin table over a floor). The slack
    // (a tenth of the radius) lets curved surfaces of curvature radius above ~5 R through.
    const float slack = 0.1f * static_cast<float>(std::sqrt(gather_r2));
    uint32_t found = 0;
    const bool no_camera_leg = vp.camera_ns == 0;  // the photon's own bucket (PhotonRecord::bucket)
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
        const int s = layout.slot_of_bucket(no_camera_leg ? ph.bucket : bucket(ph.t_ns + vp.camera_ns));
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
