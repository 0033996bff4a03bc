#include "stages/render/visible_points.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/rng.h"
#include "core/scattering.h"

namespace sl {

void VisiblePoints::resize(size_t n, bool camera_time) {
    for (auto* v : {&px, &py, &pz, &wr, &wg, &wb}) v->assign(n, 0.0f);
    normal.assign(n, OctNormal{});
    camera_ns.assign(camera_time ? n : 0, 0.0);
    depth_left.assign(n, 0);
    valid.assign(n, 0);
}

namespace {

// Adds radiance arriving at time t (ns) to a pixel's slot for this pass.
inline void deposit(SectionBuffer& buffer, const Timeline& tl, size_t pixel, double t, Vec3 L) {
    int s = buffer.layout.slot_of_bucket(tl.bucket(t));
    float* acc = buffer.slot(pixel, s);
    acc[0] += L.x;
    acc[1] += L.y;
    acc[2] += L.z;
}

struct PixelTracer {
    const RenderContext& ctx;
    VisiblePoints& vps;
    SectionBuffer& buffer;
    int pass;
    CameraSegments* segments;         // with a medium, when the beam estimate wants them
    const HomogeneousMedium* medium;  // null in vacuum
    uint64_t rays = 0;

    void trace(size_t pixel) {
        const SceneDesc& sc = ctx.scene;
        Rng rng(sc.render.seed, 1, static_cast<uint64_t>(pass), pixel);
        float fx = static_cast<float>(pixel % ctx.width) + rng.uniform();
        float fy = static_cast<float>(pixel / ctx.width) + rng.uniform();
        Vec3 o = ctx.camera.position(), d = ctx.camera.direction(fx, fy);
        Vec3 beta(1);
        double leg_ns = 0;  // camera leg so far, in ns (light crosses glass at c/n)
        bool inside = false;
        float inside_ior = 1;
        int specular = 0;
        float tnear = 0;
        vps.valid[pixel] = 0;
        if (segments) segments->count[pixel] = 0;
        const bool tof = sc.render.camera_tof;
        for (;;) {
            SurfaceHit hit;
            ++rays;
            const bool found = ctx.geometry.intersect(o, d, tnear, 1e30f, hit);
            // Dielectric solids hold no medium: only pieces outside them cross it.
            if (medium && !inside) cross_medium(pixel, o, d, tnear, found ? hit.t : 1e30f, leg_ns, specular, beta);
            if (!found) return;
            leg_ns += hit.t * (inside ? inside_ior : 1.0f) / kSpeedOfLight;
            if (hit.light >= 0) {  // an emitter seen directly (or through specular surfaces)
                const LightDesc& l = sc.lights[hit.light];
                if (dot(d, cross(l.edge1, l.edge2)) < 0)
                    deposit(buffer, ctx.timeline, pixel, tof ? leg_ns : 0.0, beta * l.radiance);
                return;
            }
            const MaterialDesc& m = sc.materials[hit.material];
            Vec3 nf = dot(d, hit.normal) < 0 ? hit.normal : -hit.normal;
            if (m.type == MaterialType::Diffuse) {
                store_visible_point(pixel, hit.position, hit.t, nf, beta * m.albedo, leg_ns, specular, rng);
                return;
            }
            if (++specular >= sc.render.max_depth) return;
            SpecularBounce b = specular_bounce(m, d, hit.normal, inside, rng);
            beta *= b.weight;
            if (b.inside_after != inside) inside_ior = m.ior;
            inside = b.inside_after;
            Vec3 side = dot(b.direction, hit.normal) > 0 ? hit.normal : -hit.normal;
            o = hit.position + side * ray_epsilon(hit.position, hit.t);
            d = b.direction;
            tnear = 0;
            if (is_black(beta)) return;
        }
    }

    // Records the piece of o + t d, t in (tnear, tfar), inside the medium and attenuates the
    // path's throughput by its transmittance.
    void cross_medium(size_t pixel, Vec3 o, Vec3 d, float tnear, float tfar, double leg_ns, int specular, Vec3& beta) {
        float t0, t1;
        if (!medium->clip(o, d, tnear, tfar, t0, t1)) return;
        if (segments && segments->count[pixel] < CameraSegments::kPerPixel) {
            CameraSegment& s = segments->segments[pixel * CameraSegments::kPerPixel + segments->count[pixel]++];
            s.origin = o + d * t0;
            s.dir = d;
            s.length = t1 - t0;
            s.beta = beta;
            s.depth_left = static_cast<uint32_t>(ctx.scene.render.max_depth - specular);
            s.camera_ns = leg_ns + t0 / kSpeedOfLight;
        }
        beta *= medium->transmittance(t1 - t0);
    }

    void store_visible_point(size_t pixel, Vec3 p, float hit_t, Vec3 nf, Vec3 albedo_beta, double leg_ns,
                             int specular, Rng& rng) {
        const SceneDesc& sc = ctx.scene;
        const bool tof = sc.render.camera_tof;
        const double back_ns = tof ? leg_ns : 0.0;
        Vec3 f = albedo_beta * (1.0f / kPi);  // Lambertian BRDF times camera throughput
        vps.px[pixel] = p.x; vps.py[pixel] = p.y; vps.pz[pixel] = p.z;
        vps.normal[pixel] = encode_normal(nf);
        vps.wr[pixel] = f.x; vps.wg[pixel] = f.y; vps.wb[pixel] = f.z;
        if (tof) vps.camera_ns[pixel] = back_ns;
        vps.depth_left[pixel] = static_cast<uint16_t>(sc.render.max_depth - specular);
        vps.valid[pixel] = 1;
        if (!buffer.ambient.empty()) {
            Vec3 a = albedo_beta * sc.render.ambient;
            float* amb = &buffer.ambient[pixel * 3];
            amb[0] += a.x; amb[1] += a.y; amb[2] += a.z;
        }
        // Direct light: one shadow ray per light, arriving after the light-to-point length.
        Vec3 origin = p + nf * ray_epsilon(p, hit_t);  // the hit's error grows with the ray's length
        for (size_t i = 0; i < ctx.lights.count(); ++i) {
            DirectLightSample s;
            float u1 = rng.uniform(), u2 = rng.uniform();
            if (!ctx.lights.sample_direct(i, p, nf, u1, u2, s)) continue;
            ++rays;
            if (ctx.geometry.occluded(origin, s.to_light, 0, s.distance * (1 - 1e-4f))) continue;
            double t = s.distance / kSpeedOfLight + back_ns;
            Vec3 e = s.irradiance;
            if (medium) e *= medium->transmittance(origin, s.to_light, s.distance);
            deposit(buffer, ctx.timeline, pixel, t, f * e);
        }
    }
};

}  // namespace

void camera_pass(const RenderContext& ctx, int pass, VisiblePoints& vps, SectionBuffer& buffer,
                 CameraPassCounters& counters, CameraSegments* segments) {
    if (vps.valid.size() != ctx.pixels()) vps.resize(ctx.pixels(), ctx.scene.render.camera_tof);
    const HomogeneousMedium* medium = ctx.medium ? &*ctx.medium : nullptr;
    if (!medium) segments = nullptr;
    if (segments && segments->pixels() != ctx.pixels()) segments->resize(ctx.pixels());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, ctx.pixels(), 256), [&](const tbb::blocked_range<size_t>& r) {
        PixelTracer tracer{ctx, vps, buffer, pass, segments, medium};
        for (size_t p = r.begin(); p != r.end(); ++p) tracer.trace(p);
        counters.rays.fetch_add(tracer.rays, std::memory_order_relaxed);
    });
}

}  // namespace sl
