#include "stages/render/camera_pass.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <vector>
#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

#include "core/glossy_path.h"
#include "core/rng.h"
#include "core/specular_path.h"
#include "core/surface_material.h"
#include "stages/render/beam_splat.h"
#include "stages/render/direct_by_frames.h"
#include "stages/render/single_scatter.h"

namespace sl {

namespace {

// A cheap clock for splitting the pass's time between its parts, on a sample of the pixels.
constexpr size_t kTimedEvery = 8;
inline uint64_t cycle_clock() {
#if defined(__x86_64__) || defined(__i386__)
    return __rdtsc();
#else
    return static_cast<uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
#endif
}

// Adds radiance arriving at time t (ns) to a pixel's slot for this pass (queued, in order with
// the pixel's gathered photons).
inline void deposit(SectionBuffer& buffer, DepositQueue& deposits, const Timeline& tl, size_t pixel, double t, Vec3 L) {
    const int s = buffer.layout.slot_of_bucket(tl.bucket(t));
    if (s < 0) return;  // a time this section keeps nothing for
    deposits.add(buffer.slot(pixel, s), L.x, L.y, L.z);
}

// Multiple importance sampling (Veach 1997, the power heuristic) of the two ways a followed
// glossy vertex finds an area emitter: a light sample (density p_light) and the BSDF's own
// direction meeting it (p_bsdf). Each counts with weight p^2 / (p_light^2 + p_bsdf^2), so a
// sharp lobe is not left to light samples alone (fireflies through rough glass).
inline float power_heuristic(float p, float other) {
    if (!(p > 0)) return 0;
    if (!(other > 0)) return 1;
    const float r = other / p;
    return 1 / (1 + r * r);
}

// The leg after a followed glossy vertex, for the emitter it may meet: the density its
// direction was drawn with, and whether the vertex's light samples could have drawn it too.
struct MisLeg {
    float bsdf_pdf = 0;
    bool on = false;       // weighing at all (RenderContext::glossy_mis); off: light samples alone
    bool lights_cover = true;
    // The share of an emitter's light met along this leg, p_light its light-sample density there.
    float share(float p_light) const {
        if (!on) return 0;
        return lights_cover ? power_heuristic(bsdf_pdf, p_light) : 1.0f;
    }
};

struct PixelTracer {
    const RenderContext& ctx;
    SectionBuffer& buffer;
    int pass;
    const HomogeneousMedium* medium;  // null in vacuum
    DepositQueue& deposits;
    const VolumePhotonMap* volume;    // this pass's volume photons (null in vacuum)
    int64_t emitted = 0;              // photon paths traced this pass
    BeamCounters beam{};
    SingleScatterCounters single{};
    uint64_t rays = 0;
    // The pixel's visible points this pass, for the estimates at the paths' ends (one, or one
    // per branch of a split path; reused from pixel to pixel, so no allocation per path).
    std::vector<VisiblePoint> points;
    // The pixel whose first direct-light samples of the pass are stratified over the passes
    // (light_pass_point); -1 once they are taken, or with RenderContext::stratified_light_points off.
    int64_t light_points_pixel = -1;
    // The same for the light samples of the in-scattering along the pixel's first camera
    // segment in the medium (CameraSegment::stratified_pixel).
    int64_t segment_points_pixel = -1;
    // Where the pixel's segment from the camera goes when the photons' side estimates it
    // (BeamSplat), instead of searching the tree; null once it is taken, or without the splat.
    CameraSegment* first_segment = nullptr;
    bool timed = false;               // count the cycles spent on in-scattering for this pixel
    uint64_t medium_cycles = 0;       // of this pixel (when timed)

    size_t local = 0;  // the pixel's index in the buffer (its own, or its rank's share)

    // A camera path between two vertices.
    struct PathState {
        Vec3 o, d, beta;
        double leg_ns = 0;  // camera leg so far, in ns (light crosses glass at c/n)
        bool inside = false;
        float inside_ior = 1;
        int specular = 0;
        float tnear = 0;
        // The last vertex was a followed glossy one whose light samples already counted the
        // emitters on the side this leg leaves by: an emitter it meets adds only its share by
        // the power heuristic (MisLeg), or nothing without multiple importance sampling.
        bool direct_done = false;
        MisLeg mis;
        // This leg leaves a followed glossy vertex at max_depth: it is traced only for the
        // emitter it may meet (that vertex's direct light, by multiple importance sampling).
        bool last_leg = false;
        // The path has not split yet (RenderContext::glossy_split); a branch's share of the
        // pixel's pass: its visible point's weight in the radius's statistics.
        bool may_split = true;
        float share = 1;
        // A branch's draw for its next glossy vertex, stratified over the split's branches
        // (shuffled_draw); used once, by the first followed glossy vertex after the split.
        bool has_next_draw = false;
        BsdfDraw next_draw{};
    };

    // `pixel`: in the image (it picks the random stream and the ray); `local_pixel`: in the buffer.
    void trace(size_t pixel, size_t local_pixel) {
        local = local_pixel;
        points.clear();
        medium_cycles = 0;
        Rng rng(ctx.render.seed, 1, static_cast<uint64_t>(pass), pixel);
        light_points_pixel = ctx.stratified_light_points ? static_cast<int64_t>(pixel) : -1;
        segment_points_pixel = light_points_pixel;
        float fx = static_cast<float>(pixel % ctx.width), fy = static_cast<float>(pixel / ctx.width);
        float weight = 1;
        if (!jitter(pixel, fx, fy, rng, weight)) return;
        PathState st;
        st.o = ctx.camera.position();
        st.d = ctx.camera.direction(fx, fy);
        st.beta = Vec3(weight);
        walk(st, rng);
    }

    // Follows the path from st's leg to its end (a visible point, an emitter, nothing).
    void walk(PathState& st, Rng& rng) {
        const RenderDesc& settings = ctx.render;
        const bool tof = settings.camera_tof;
        for (;;) {
            SurfaceHit hit;
            ++rays;
            const Vec3 o = st.o, d = st.d;
            const bool found = ctx.geometry.intersect(o, d, st.tnear, 1e30f, hit);
            // Dielectric solids hold no medium: only pieces outside them cross it.
            if (medium && !st.inside) {
                if (st.last_leg)
                    st.beta *= medium->transmittance(o, d, found ? hit.t : 1e30f);  // nothing scatters beyond the cap
                else
                    cross_medium(o, d, st.tnear, found ? hit.t : 1e30f, st.leg_ns, st.specular, st.beta, rng);
            }
            if (!found) return;
            st.leg_ns += hit.t * (st.inside ? st.inside_ior : 1.0f) / kSpeedOfLight;
            const double at_ns = tof ? st.leg_ns : 0.0;
            if (hit.light >= 0) {  // an emitter seen directly (or through specular surfaces)
                const size_t l = static_cast<size_t>(hit.light);
                const float share = st.direct_done ? st.mis.share(ctx.lights.quad_pdf(l, d, hit.t)) : 1.0f;
                if (share > 0 && ctx.lights.quad_front_seen(l, d))
                    deposit(buffer, deposits, ctx.timeline, local, at_ns, st.beta * ctx.lights.quad_radiance(l) * share);
                return;
            }
            const SurfaceMaterial& m = ctx.materials[hit.material];
            const bool toward = dot(d, hit.normal) < 0;
            Vec3 nf = toward ? hit.normal : -hit.normal;
            if (m.emits()) {  // an emissive mesh seen directly (or through specular surfaces)
                const float share =
                    st.direct_done
                        ? st.mis.share(ctx.lights.emitter_pdf(ctx.scene.materials[static_cast<size_t>(hit.material)], d,
                                                              hit.normal, hit.t))
                        : 1.0f;
                Vec3 le = share > 0 ? emission_at(m, hit, d) : Vec3(0);
                if (!is_black(le)) deposit(buffer, deposits, ctx.timeline, local, at_ns, st.beta * le * share);
            }
            if (st.last_leg) return;
            if (m.type == MaterialType::Diffuse) {
                Vec3 ns = toward ? hit.shading_normal : -hit.shading_normal;
                const Vec3 nm = m.normal_texture ? shading_normal_facing(m, hit, d) : ns;
                store_visible_point(hit.position, hit.t, nf, ns, nm, st.beta * albedo_at(m, hit), st, rng);
                return;
            }
            st.direct_done = false;
            bsdf::Bsdf b;  // GGX: the BSDF at the hit (textures applied)
            GlossyUse use = GlossyUse::None;
            if (m.glossy != GlossyUse::None) {
                b = bsdf_at(m, hit);
                use = glossy_use_at(m, b);
            }
            if (use == GlossyUse::Gather) {
                Vec3 ns = toward ? hit.shading_normal : -hit.shading_normal;
                const Vec3 nm = m.normal_texture ? shading_normal_facing(m, hit, d) : ns;
                if (!ctx.follow_coats || !smooth_coat(b)) {
                    store_glossy_point(hit, b, nf, ns, nm, d, st, rng);
                    return;
                }
                // A smooth coat over a diffuse base: the base gathers here, the coat's
                // reflection is followed (a sharp lobe weighing the photons is what made the
                // gather noisy), each half of the one BSDF.
                bsdf::Bsdf base = b;
                base.no_specular = true;
                store_glossy_point(hit, base, nf, ns, nm, d, st, rng);
                b.no_diffuse = true;
                use = GlossyUse::Follow;
            }
            if (use != GlossyUse::Follow) {
                if (++st.specular >= settings.max_depth) return;
                const Vec3 w = follow_specular(m, hit, st.o, st.d, st.inside, st.inside_ior, rng);
                if (!go_on(st, w, rng)) return;
                continue;
            }
            // Direct light here (f(wo, wi) |cos|), on the outside of a surface with an inside;
            // then on along sampled directions (n of them where the path splits), each a bounce.
            // A followed coat goes on in one leg: more left the plastic cube's spread as it was.
            const int split = b.no_diffuse  ? 1
                              : has_inside(b) ? ctx.glossy_split_transmissive
                                              : ctx.glossy_split;
            const int n = st.may_split ? std::max(1, split) : 1;
            const Vec3 n_out = frame_normal(m, b, hit, d, st.inside);
            const Vec3 nf_out = has_inside(b) && st.inside ? -nf : nf;
            const LocalFrame frame(n_out);
            const Vec3 wo = frame.local(-d);
            // At max_depth the path still draws its direction, for the emitter it may meet.
            const bool weigh = ctx.glossy_mis;
            const Vec3 beta = st.beta;
            direct_light(hit.position, hit.t, nf_out, n_out, at_ns, rng, [&](Vec3 wi, float light_pdf) {
                const Vec3 wl = frame.local(wi);
                // light_pdf 0: a point, spot or sun, which no drawn direction meets: all its own.
                // n drawn directions weigh as one of n times the density.
                const float share =
                    weigh && light_pdf > 0 ? power_heuristic(light_pdf, n * bsdf::pdf(b, wo, wl)) : 1.0f;
                return beta * bsdf::eval(b, wo, wl) * share;
            });
            st.last_leg = ++st.specular >= settings.max_depth;
            if (st.last_leg && !weigh) return;
            if (n > 1) {  // the branches, each with 1/n of the path's weight, and done
                const BsdfDraw offset{rng.uniform(), rng.uniform(), rng.uniform()};
                const BsdfDraw next_offset{rng.uniform(), rng.uniform(), rng.uniform()};
                const BranchShuffle shuffle{rng.next_u32() | 1u, rng.next_u32()};
                for (int k = 0; k < n; ++k) {
                    PathState branch = st;
                    branch.may_split = false;
                    branch.has_next_draw = true;
                    branch.next_draw = shuffled_draw(k, n, shuffle, next_offset);
                    branch.beta = st.beta * (1.0f / static_cast<float>(n));
                    branch.share = st.share / static_cast<float>(n);
                    if (follow(branch, m, b, hit, nf_out, n_out, n, weigh, stratified_draw(k, n, offset), rng))
                        walk(branch, rng);
                }
                return;
            }
            BsdfDraw u;
            if (st.has_next_draw) {
                u = st.next_draw;
                st.has_next_draw = false;
            } else {
                u = BsdfDraw{rng.uniform(), rng.uniform(), rng.uniform()};
            }
            if (!follow(st, m, b, hit, nf_out, n_out, 1, weigh, u, rng)) return;
        }
    }

    // The path on from a followed glossy vertex along a direction sampled with u (one of n drawn
    // there); false when it ends.
    bool follow(PathState& st, const SurfaceMaterial& m, const bsdf::Bsdf& b, const SurfaceHit& hit, Vec3 nf_out,
                Vec3 n_out, int n, bool weigh, BsdfDraw u, Rng& rng) {
        float pdf = 0;
        const Vec3 w = follow_glossy(m, b, hit, st.o, st.d, st.inside, st.inside_ior, u, bsdf::Transport::Radiance, &pdf);
        st.direct_done = dot(st.d, nf_out) > 0;
        // The light samples' side is also the shading normal's: beyond it they draw nothing.
        st.mis = MisLeg{n * pdf, weigh, dot(st.d, n_out) > 0};
        return go_on(st, w, rng);
    }

    // The throughput after a bounce of weight w, and Russian roulette from the third specular
    // bounce on, on the event's weight (clear glass and perfect mirrors weigh 1 and are never
    // cut: max_depth is their cap). False when the path ends.
    bool go_on(PathState& st, Vec3 w, Rng& rng) {
        st.beta *= w;
        st.tnear = 0;
        if (is_black(st.beta)) return false;
        const float q = st.specular >= 3 ? std::min(1.0f, max_component(w)) : 1.0f;
        if (q < 1) {
            if (rng.uniform() >= q) return false;
            st.beta = st.beta * (1.0f / q);
        }
        return true;
    }

    // The ray's point in the pixel (x, y): uniform, except in the pixels within kStratified
    // pixels of a point light's image in the haze, where a ray passing at h from the light sees
    // in-scattering ~ 1/h, which dominates the image's sum. There the point is stratified over
    // the passes (below), and within kLightImage pixels of the image, where uniform jitter has a
    // variance that grows without bound (log(pixel / h)), every other pass draws it with density
    // q ~ 1 / (distance to the light's image) in a disc of kLightImage pixels round it (a ray then
    // passes at h in proportion) and the others uniformly; every contribution is weighted by
    // 1 / (the mixture's density, 1/2 + q/2). Rays drawn outside the pixel count as zero.
    // False: nothing to trace.
    static constexpr float kLightImage = 1.0f;
    static constexpr float kStratified = 3.0f;
    bool jitter(size_t pixel, float& fx, float& fy, Rng& rng, float& weight) const {
        const float x0 = fx, y0 = fy;
        const std::array<float, 2>* near = nullptr;
        for (const std::array<float, 2>& c : ctx.light_images)
            if (c[0] > x0 - kStratified && c[0] < x0 + 1 + kStratified && c[1] > y0 - kStratified &&
                c[1] < y0 + 1 + kStratified) {
                near = &c;
                break;
            }
        if (!near) {
            // Pass after pass, the pixel's points fill it evenly (pass_point): a pixel across a
            // sharp shadow or a silhouette gets its coverage right far sooner than from
            // independent points (the floor at a cube's corner: 64 of them left 30 % noise).
            const StratumPoint u = pass_point(pixel, false);
            fx = x0 + u.a;
            fy = y0 + u.b;
            return true;
        }
        const bool disc = (*near)[0] > x0 - kLightImage && (*near)[0] < x0 + 1 + kLightImage &&
                          (*near)[1] > y0 - kLightImage && (*near)[1] < y0 + 1 + kLightImage;
        const StratumPoint u = pass_point(pixel, disc);
        if (!u.toward_light) {
            fx = x0 + u.a;
            fy = y0 + u.b;
            if (!disc) return true;
        } else {
            const float r = kLightImage * u.a, phi = 2 * kPi * u.b;
            fx = (*near)[0] + r * std::cos(phi);
            fy = (*near)[1] + r * std::sin(phi);
            if (!(fx >= x0 && fx < x0 + 1 && fy >= y0 && fy < y0 + 1)) return false;
        }
        const float dx = fx - (*near)[0], dy = fy - (*near)[1];
        const float rc = std::sqrt(dx * dx + dy * dy);
        const float q = rc < kLightImage ? 1 / (2 * kPi * kLightImage * rc) : 0.0f;  // 1/r in the disc
        weight = 1 / (0.5f + 0.5f * q);
        return std::isfinite(weight) && weight > 0;
    }

    // The pass's point of a pixel round a light's image, stratified over the passes: the n-th
    // point of Roberts' R2 sequence (n = pass, or pass / 2 when alternate passes take the
    // uniform and the disc density), shifted modulo 1 by a rotation drawn for this pixel and
    // seed (its own random stream, the same in every pass; the disc's points have their own, or
    // the two halves would share their errors). For every pass the point is
    // uniform (the rotation is) and the choice of density is 1/2 each (its parity is drawn),
    // so each pass's estimate is unbiased and seeds are independent; over the passes the points
    // fill the pixel (or disc) evenly instead of clumping, which is what the 1/h peak needs.
    struct StratumPoint {
        float a, b;
        bool toward_light;
    };
    StratumPoint pass_point(size_t pixel, bool disc) const {
        Rng rotation(ctx.render.seed, 11, 0, pixel);
        const uint64_t parity = rotation.next_u32() & 1u;
        uint64_t n = static_cast<uint64_t>(pass);
        bool toward = false;
        if (disc) {
            toward = ((n + parity) & 1u) != 0;
            n >>= 1;
        }
        if (toward) {  // the disc's points: their own rotation
            rotation.uniform();
            rotation.uniform();
        }
        const double ra = rotation.uniform(), rb = rotation.uniform();
        constexpr double g = 1.32471795724474602596;  // the plastic number: R2's generator
        const double a = ra + static_cast<double>(n) / g, b = rb + static_cast<double>(n) / (g * g);
        const float fa = static_cast<float>(a - std::floor(a)), fb = static_cast<float>(b - std::floor(b));
        return {std::min(fa, 0x1.fffffep-1f), std::min(fb, 0x1.fffffep-1f), toward};
    }

    // The light sample of the pixel's first vertex in this pass: point `pass` of the Halton
    // sequence in bases 2 and 3, shifted modulo 1 by an offset drawn for this pixel, light and
    // seed (the same in every pass). Each pass's sample is uniform (the offset is), so the
    // estimate keeps its mean; over the passes a pixel's samples cover the light evenly. In a
    // soft shadow, where part of a lamp is hidden, independent samples leave the hidden share a
    // binomial count (64 passes: ~6 % a pixel); stratified, it converges far faster. Halton, not
    // the R2 sequence of the pixel's point: the same sequence in both would tie each position in
    // the pixel to one spot on the lamp for every pass.
    void light_pass_point(size_t pixel, size_t light, float& u1, float& u2) const {
        halton_pass_point(ctx.render.seed, 12, light, pixel, static_cast<uint32_t>(pass), u1, u2);
    }

    // The piece of o + t d, t in (tnear, tfar), inside the medium: its in-scattering at once
    // (single scattering by next-event estimation, unless the photons carry it; then the beam
    // estimate of the volume photons), and the path's throughput attenuated by its transmittance.
    // Every piece gathers, however many specular bounces came before it.
    void cross_medium(Vec3 o, Vec3 d, float tnear, float tfar, double leg_ns, int specular, Vec3& beta, Rng& rng) {
        float t0, t1;
        if (!medium->clip(o, d, tnear, tfar, t0, t1)) return;
        const uint64_t c0 = timed ? cycle_clock() : 0;
        CameraSegment s;
        s.origin = o + d * t0;
        s.dir = d;
        s.length = t1 - t0;
        s.beta = beta;
        s.depth_left = static_cast<uint32_t>(ctx.render.max_depth - specular);
        s.camera_ns = leg_ns + t0 / kSpeedOfLight;
        s.stratified_pixel = segment_points_pixel;
        s.pass = static_cast<uint32_t>(pass);
        segment_points_pixel = -1;
        if (!ctx.single_scatter_by_photons) {
            const uint64_t before = single.shadow_rays;
            single_scatter_along(ctx, s, rng, buffer, deposits, local, single);
            rays += single.shadow_rays - before;
        }
        const Vec3 eye = ctx.camera.position();
        const bool from_camera =
            first_segment && specular == 0 && leg_ns == 0 && o.x == eye.x && o.y == eye.y && o.z == eye.z;
        if (volume && from_camera) {
            *first_segment = s;  // estimated with the range's other pixels (BeamSplat::gather)
        } else if (volume) {
            deposits.drain();  // the beam estimate adds to the pixel's slots directly
            gather_volume_at(ctx, s, *volume, emitted, local, buffer, beam);
        }
        first_segment = nullptr;
        beta *= medium->transmittance(t1 - t0);
        if (timed) medium_cycles += cycle_clock() - c0;
    }

    // nf: the geometric normal facing the path (ray offsets, side tests); ns: the shading
    // normal on the same side (gathering); nm: ns with the material's normal map (the BRDF's cosines).
    void store_visible_point(Vec3 p, float hit_t, Vec3 nf, Vec3 ns, Vec3 nm, Vec3 albedo_beta, const PathState& st,
                             Rng& rng) {
        const RenderDesc& settings = ctx.render;
        const bool tof = settings.camera_tof;
        const double back_ns = tof ? st.leg_ns : 0.0;
        Vec3 f = albedo_beta * (1.0f / kPi);  // Lambertian BRDF times camera throughput
        points.push_back(VisiblePoint{p, ns, f, back_ns, static_cast<uint32_t>(settings.max_depth - st.specular)});
        points.back().share = st.share;
        if (!buffer.ambient.empty()) {
            Vec3 a = albedo_beta * settings.ambient;
            float* amb = &buffer.ambient[local * 3];
            amb[0] += a.x; amb[1] += a.y; amb[2] += a.z;
        }
        direct_light(p, hit_t, nf, nm, back_ns, rng, [&](Vec3, float) { return f; }, &f);
    }

    // Direct light at p: one shadow ray per light, arriving after the light-to-point length;
    // weight(to_light, the sample's solid-angle density) turns the irradiance (cosine on ns included) into the pixel's radiance.
    // diffuse: at a Lambertian point, that weight itself (the same for every direction), so that
    // a pulsed quad may be sampled frame by frame (direct_by_frames.h).
    template <class Weight>
    void direct_light(Vec3 p, float hit_t, Vec3 nf, Vec3 ns, double back_ns, Rng& rng, Weight&& weight,
                      const Vec3* diffuse = nullptr) {
        Vec3 origin = p + nf * ray_epsilon(p, hit_t);  // the hit's error grows with the ray's length
        const bool carried = buffer.layout.carried;
        const int64_t stratified_pixel = light_points_pixel;
        light_points_pixel = -1;  // the path's later vertices draw theirs at random
        const bool by_frames = ctx.pulse_direct_by_frames && ctx.emission == EmissionMode::Pulse;
        for (size_t i = 0; i < ctx.lights.count(); ++i) {
            DirectLightSample s;
            // Drawn even when replaced: the path's later numbers stay the same either way.
            float u1 = rng.uniform(), u2 = rng.uniform();
            if (stratified_pixel >= 0) light_pass_point(static_cast<size_t>(stratified_pixel), i, u1, u2);
            // A carried section keeps nothing that arrives before it: a light whose every
            // sample would is not even sampled.
            if (carried && ctx.timeline.bucket(ctx.lights.latest_arrival_ns(i, p) + back_ns) < buffer.layout.first_bucket)
                continue;
            if (diffuse && by_frames &&
                quad_direct_by_frames(ctx, i, p, origin, nf, ns, back_ns, u1, u2, *diffuse, buffer, deposits, local, rays))
                continue;
            if (!ctx.lights.sample_direct(i, p, ns, u1, u2, s)) continue;
            if (dot(s.to_light, nf) <= 0) continue;  // below the true surface: no leak through it
            const double t = s.start_ns + s.distance / kSpeedOfLight + back_ns;
            // A section that keeps no slot for this arrival (an early section, light arriving
            // after its end) would drop it: no shadow ray is needed to find that out.
            if (buffer.layout.slot_of_bucket(ctx.timeline.bucket(t)) < 0) continue;
            ++rays;
            if (ctx.geometry.occluded_to(origin, p + s.to_light * s.distance)) continue;
            Vec3 e = s.irradiance;
            if (medium) e *= medium->transmittance(origin, s.to_light, s.distance);
            deposit(buffer, deposits, ctx.timeline, local, t, weight(s.to_light, s.pdf) * e);
        }
    }

    // A visible point on a GGX surface that gathers (docs/materials.md): the throughput and the
    // BSDF at the point, evaluated for each light sample and, in the gather, for each photon.
    void store_glossy_point(const SurfaceHit& hit, const bsdf::Bsdf& b, Vec3 nf, Vec3 ns, Vec3 nm, Vec3 d,
                            const PathState& st, Rng& rng) {
        const RenderDesc& settings = ctx.render;
        const double back_ns = settings.camera_tof ? st.leg_ns : 0.0;
        const Vec3 beta = st.beta;
        VisiblePoint& vp = points.emplace_back();
        vp = VisiblePoint{hit.position, ns, beta, back_ns, static_cast<uint32_t>(settings.max_depth - st.specular)};
        vp.share = st.share;
        vp.glossy = true;
        vp.bsdf = b;
        vp.wo = -d;
        vp.bsdf_normal = nm;
        if (!buffer.ambient.empty()) {
            Vec3 a = beta * b.base * settings.ambient;
            float* amb = &buffer.ambient[local * 3];
            amb[0] += a.x; amb[1] += a.y; amb[2] += a.z;
        }
        const LocalFrame frame(nm);
        const Vec3 wo = frame.local(-d);
        direct_light(hit.position, hit.t, nf, nm, back_ns, rng,
                     [&](Vec3 wi, float) { return beta * bsdf::eval(b, wo, frame.local(wi)); });
    }
};

}  // namespace

CameraPassTimes camera_pass(const RenderContext& ctx, int pass, const PassPhotons& photons, SectionBuffer& buffer,
                            CameraPassCounters& counters) {
    const HomogeneousMedium* medium = ctx.medium ? &*ctx.medium : nullptr;
    const VolumePhotonMap* volume = medium ? photons.volume : nullptr;
    struct Work {
        double max_r2 = 0;
        uint64_t camera_paths = 0, volume = 0, gather = 0;  // cycles
    };
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t cpu0 = std::clock();
    const bool splat = volume && ctx.beam_splat;
    BeamSplat splatted;
    const uint64_t splat_c0 = cycle_clock();
    if (splat) splatted.build(ctx, *volume, buffer);
    // Counted with the sampled pixels' cycles, at their rate (one pixel in kTimedEvery).
    const uint64_t splat_build = (cycle_clock() - splat_c0) / kTimedEvery;
    Work total = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, buffer.radius2.size(), 256), Work{},  // this rank's pixels
        [&](const tbb::blocked_range<size_t>& r, Work w) {
            DepositQueue deposits;  // drained when it goes out of scope, at the range's end
            PixelTracer tracer{ctx, buffer, pass, medium, deposits, volume, photons.emitted};
            const PixelShare share = buffer.share;
            // The range's segments from the camera, for the beam estimate from the photons' side.
            std::vector<CameraSegment> first(splat ? r.size() : 0);
            for (size_t p = r.begin(); p != r.end(); ++p) {
                if (splat) tracer.first_segment = &first[p - r.begin()];
                // The split between the parts is sampled on one pixel in kTimedEvery: reading
                // the clock four times a pixel cost as much as a sixth of the pass.
                const bool timed = p % kTimedEvery == 0;
                tracer.timed = timed;
                const uint64_t c0 = timed ? cycle_clock() : 0;
                tracer.trace(share.global(p), p);
                const uint64_t c1 = timed ? cycle_clock() : 0;
                for (const VisiblePoint& vp : tracer.points)
                    gather_surface_at(ctx, vp, photons.surface, photons.emitted, p, buffer, deposits);
                w.max_r2 = std::max(w.max_r2, buffer.radius2[p]);
                if (timed) {
                    const uint64_t c2 = cycle_clock();
                    w.camera_paths += c1 - c0 - tracer.medium_cycles;
                    w.volume += tracer.medium_cycles;
                    w.gather += c2 - c1;
                }
            }
            if (splat) {
                deposits.drain();  // the pixels' other light first: each pixel's sums keep one order
                const uint64_t c0 = cycle_clock();
                splatted.gather(ctx, *volume, photons.emitted, r.begin(), r.end(), first, buffer, tracer.beam);
                w.volume += (cycle_clock() - c0) / kTimedEvery;
            }
            counters.rays.fetch_add(tracer.rays, std::memory_order_relaxed);
            counters.beam_segments.fetch_add(tracer.beam.segments, std::memory_order_relaxed);
            counters.beam_hits.fetch_add(tracer.beam.photon_hits, std::memory_order_relaxed);
            counters.single_scatter_samples.fetch_add(tracer.single.samples, std::memory_order_relaxed);
            return w;
        },
        [](Work a, const Work& b) {
            a.max_r2 = std::max(a.max_r2, b.max_r2);
            a.camera_paths += b.camera_paths;
            a.volume += b.volume;
            a.gather += b.gather;
            return a;
        });
    total.volume += splat_build;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
    buffer.max_radius = std::sqrt(total.max_r2);
    if (medium) buffer.volume_radius2 *= volume_radius_shrink(buffer.passes_done, ctx.render.alpha);
    ++buffer.passes_done;

    CameraPassTimes times;
    const double cycles = static_cast<double>(total.camera_paths + total.volume + total.gather);
    if (cycles > 0) {
        times.camera_paths = wall * static_cast<double>(total.camera_paths) / cycles;
        times.volume = wall * static_cast<double>(total.volume) / cycles;
        times.gather = wall * static_cast<double>(total.gather) / cycles;
        times.volume_cpu = cpu * static_cast<double>(total.volume) / cycles;
    }
    return times;
}

}  // namespace sl
