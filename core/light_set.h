#pragma once
// The scene's lights: photon emission (a light chosen in proportion to its power) and the
// direct-light sample that the camera pass evaluates at each visible point.
#include <vector>

#include "config/scene_desc.h"
#include "core/emissive_triangles.h"
#include "core/rng.h"
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
    // One sample of light i's direct irradiance at p (unit normal n facing the viewer); false
    // when light i cannot reach p this way (back side, outside a spot's cone, a laser,
    // a sun below the horizon).
    bool sample_direct(size_t i, Vec3 p, Vec3 n, float u1, float u2, DirectLightSample& out) const;
    // No sample of light i arrives at p later than this (ns; +infinity where no cheap bound is
    // known: suns, emissive meshes). A carried section skips lights whose light is all earlier.
    double latest_arrival_ns(size_t i, Vec3 p) const;
    // Quad light i seen along d (a camera path hitting it): whether its front (edge1 x edge2,
    // the stored normal) faces the viewer, and the radiance it then sends.
    bool quad_front_seen(size_t i, Vec3 d) const { return dot(d, lights_[i].normal) < 0; }
    Vec3 quad_radiance(size_t i) const { return lights_[i].desc.radiance; }

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
    };
    const Light& pick(float u, float& probability) const;

    std::vector<Light> lights_;
    EmissiveTriangles emitters_;
    std::vector<float> cdf_;  // cumulative choice probability by average power
    float total_power_ = 0;
};

}  // namespace sl
