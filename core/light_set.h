#pragma once
// The scene's lights: photon emission (a light chosen in proportion to its power) and the
// direct-light sample that the camera pass evaluates at each visible point.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "config/scene_desc.h"
#include "core/emission_aim.h"
#include "core/emissive_triangles.h"
#include "core/rng.h"
#include "core/spherical_rectangle.h"
#include "core/sun_light.h"

namespace sl {

struct EmittedPhoton {
    Vec3 origin, direction;
    Vec3 flux;             // W carried by this one emitted path (before dividing by the count)
    bool direct_by_photons;  // the light's direct light is gathered, not computed (lasers)
    double start_ns = 0;     // when the light leaves the origin (a sun's rectangle: slightly < 0)
};

struct DirectLightSample {
    Vec3 irradiance;  // W/m^2 arriving at the point from this sample, before visibility
    Vec3 to_light;    // unit direction from the point towards the light sample
    float distance = 0;
    double start_ns = 0;  // when the light left the sample's point (a sun: slightly < 0)
    // The solid-angle density of to_light under this light's sampler (quads, emissive meshes);
    // 0 for a light no path can meet by chance (point, spot, sun): multiple importance
    // sampling at glossy vertices weighs the two strategies by it.
    float pdf = 0;
};

// Light i sampled once for a camera segment in the medium (single scattering by next-event
// estimation in the camera pass): a point on it (point, spot, quad, emissive triangles) or a
// direction (sun), fixed for the whole segment, so that the arrival time along the segment has
// a closed form; then evaluated at each distance sample x.
struct InScatterLight {
    enum class Kind : uint8_t { Isotropic, Spot, OneSided, TwoSided, Sun };
    Kind kind = Kind::Isotropic;
    Vec3 position;      // the light's point (all but the sun)
    Vec3 axis;          // spot: its direction; one- or two-sided: the emitter's front normal; sun: its axis
    Vec3 emission;      // point, spot: W/sr; area: L / pdf_area (W/sr per unit cosine); sun: W/m^2 facing it
    float cos_cone = -1;  // spot
    Vec3 travel;        // sun: the sampled direction of travel
    float sun_cos = 1;  // sun: cos(travel, axis)
    float sun_lead = 0;  // sun: the rectangle's distance before the wavefront's t = 0 plane
    double sun_h0 = 0;   // sun: dot(x, axis) of the wavefront at t = 0
    double start_ns = 0;  // when the light leaves its point (a sun: -lead / (cos c))
    // A quad with edges at right angles: evaluated by a fresh point per distance sample, uniform
    // in the solid angle it subtends there (at_rect), not by `position`, which then only maps
    // the segment's arrival times.
    bool rect = false;
    Vec3 corner, edge1, edge2, radiance;

    bool point_like() const { return kind != Kind::Sun; }
    // The rect's light at x: L * Omega (the radiance over the solid-angle density, in place of the
    // irradiance), the unit direction to the sampled point and its distance; false behind it.
    bool at_rect(Vec3 x, float u, float v, Vec3& irradiance, Vec3& to_light, float& distance) const {
        if (!(dot(axis, x - corner) > 0)) return false;  // one-sided: x behind the quad
        const SphericalRectangle sr(x, corner, edge1, edge2);
        if (!(sr.solid_angle > 1e-9f)) return false;
        const Vec3 v2 = sr.sample(u, v) - x;
        const float d2 = dot(v2, v2);
        if (!(d2 > 0)) return false;
        distance = std::sqrt(d2);
        to_light = v2 / distance;
        if (!(-dot(axis, to_light) > 0)) return false;
        irradiance = radiance * sr.solid_angle;
        return true;
    }
    // The irradiance at x on a plane facing the light (W/m^2), the unit direction towards it and
    // the shadow ray's length; false when none of this sample's light reaches x.
    bool at(Vec3 x, Vec3& irradiance, Vec3& to_light, float& distance) const {
        if (kind == Kind::Sun) {
            const double along = std::max(0.0, static_cast<double>(dot(x, axis)) - sun_h0) + sun_lead;
            irradiance = emission;
            to_light = -travel;
            distance = static_cast<float>(along / sun_cos);
            return true;
        }
        const Vec3 v = position - x;
        const float d2 = dot(v, v);
        if (!(d2 > 0)) return false;
        distance = std::sqrt(d2);
        to_light = v / distance;
        float w = 1;
        switch (kind) {
        case Kind::Spot: if (dot(-to_light, axis) < cos_cone) return false; break;
        case Kind::OneSided: w = -dot(axis, to_light); break;
        case Kind::TwoSided: w = std::abs(dot(axis, to_light)); break;
        default: break;
        }
        if (!(w > 0)) return false;
        irradiance = emission * (w / d2);
        return true;
    }
};

class LightSet {
public:
    // `scene` must outlive the set (emissive meshes read its textures). Bounds: the scene's
    // extent (geometry and medium box), which a sun's light must cover and where its
    // wavefront starts.
    explicit LightSet(const SceneDesc& scene, Vec3 bounds_min = Vec3(0), Vec3 bounds_max = Vec3(0));

    bool has_emission() const { return total_power_ > 0; }
    float total_power() const { return total_power_; }
    size_t count() const { return lights_.size(); }

    EmittedPhoton emit(Rng& rng) const;
    // Where light i's photons go (emission_aim.h): a sun's aim is over where on its rectangle
    // they start, a point, spot or quad light's over which way they leave (the two uniforms
    // its direction is drawn from); lasers and emissive meshes are not aimed. An empty table
    // (the default) draws them as they are.
    bool aimable(size_t i) const;
    float power_of(size_t i) const { return average(lights_[i].power); }  // W, the channels' mean
    void aim(size_t i, EmissionAim aim) { lights_[i].aim = std::move(aim); }
    const EmissionAim& aim_of(size_t i) const { return lights_[i].aim; }
    // A photon of light i alone (its power, as if it were the only light) with its aimed pair of
    // uniforms given and not aimed: for the pilot that makes the aim.
    EmittedPhoton emit_from(size_t i, float a1, float a2, Rng& rng) const;
    // One sample of light i's direct irradiance at p (unit normal n facing the viewer); false
    // when light i cannot reach p this way (back side, outside a spot's cone, a laser,
    // a sun below the horizon).
    bool sample_direct(size_t i, Vec3 p, Vec3 n, float u1, float u2, DirectLightSample& out) const;
    // Light i sampled for in-scattering along a camera segment (InScatterLight); false for a
    // laser (a delta direction no camera ray meets: its single scattering stays with photons)
    // and for a light without power.
    // by_area: a rectangular quad too is one point of its area (`position`), as other quads are.
    bool sample_in_medium(size_t i, float u1, float u2, InScatterLight& out, bool by_area = false) const;
    // No sample of light i arrives at p later than this (ns; +infinity where no cheap bound is
    // known: suns, emissive meshes). A carried section skips lights whose light is all earlier.
    double latest_arrival_ns(size_t i, Vec3 p) const;
    // Quad light i seen along d (a camera path hitting it): whether its front (edge1 x edge2,
    // the stored normal) faces the viewer, and the radiance it then sends.
    bool quad_front_seen(size_t i, Vec3 d) const { return dot(d, lights_[i].normal) < 0; }
    Vec3 quad_radiance(size_t i) const { return lights_[i].desc.radiance; }
    // Quad light i's corner, edges and unit front normal (edge1 x edge2); false for any other light.
    bool quad_geometry(size_t i, Vec3& corner, Vec3& edge1, Vec3& edge2, Vec3& normal) const {
        const Light& l = lights_[i];
        if (l.mesh || l.desc.type != LightType::Quad) return false;
        corner = l.desc.corner, edge1 = l.desc.edge1, edge2 = l.desc.edge2, normal = l.normal;
        return true;
    }
    // The solid-angle densities with which sample_direct would have picked the point a path
    // met at distance t along unit d: on quad light i (seen from the front), or on an emissive
    // surface of material m with unit normal n (0 where it picks none).
    float quad_pdf(size_t i, Vec3 d, float t) const {
        const float cos_l = -dot(d, lights_[i].normal);
        return cos_l > 0 ? t * t / (cos_l * lights_[i].area) : 0.0f;
    }
    float emitter_pdf(const MaterialDesc& m, Vec3 d, Vec3 n, float t) const {
        const float cos_l = std::abs(dot(d, n));
        return cos_l > 0 ? emitters_.pdf_area_of(m) * t * t / cos_l : 0.0f;
    }

private:
    struct Light {
        LightDesc desc;
        Vec3 normal;        // quad: unit front normal
        float area = 0;     // quad
        float cos_cone = 1;  // spot
        Vec3 intensity;     // point/spot: W/sr
        Vec3 power;         // RGB power in W
        bool mesh = false;  // the emissive triangles of imported meshes (emitters_)
        SunLight sun;       // sun
        EmissionAim aim;    // where its photons go (empty: uniformly)
    };
    EmittedPhoton emit_light(const Light& l, float p, Rng& rng, const float* pair) const;
    const Light& pick(float u, float& probability) const;

    std::vector<Light> lights_;
    EmissiveTriangles emitters_;
    std::vector<float> cdf_;  // cumulative choice probability by average power
    float total_power_ = 0;
};

}  // namespace sl
