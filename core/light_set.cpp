#include "core/light_set.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "foundation/constants.h"
#include "foundation/errors.h"
#include "core/sampling.h"

namespace sl {

LightSet::LightSet(const SceneDesc& scene, Vec3 bounds_min, Vec3 bounds_max) : emitters_(scene) {
    for (const LightDesc& d : scene.lights) {
        Light l;
        l.desc = d;
        switch (d.type) {
        case LightType::Point:
            l.power = d.power;
            l.intensity = d.power / (4 * kPi);
            break;
        case LightType::Spot: {
            l.power = d.power;
            // 1 - cos(c) = 2 sin^2(c/2), in double: exact for narrow cones too.
            double half = 0.5 * d.cone_deg * kPiDouble / 180.0;
            double one_minus_cos = 2 * std::sin(half) * std::sin(half);
            l.cos_cone = static_cast<float>(1 - one_minus_cos);
            l.intensity = d.power * static_cast<float>(1 / (2 * kPiDouble * one_minus_cos));
            l.desc.direction = normalize(d.direction);
            break;
        }
        case LightType::Laser:
            l.power = d.power;
            l.desc.direction = normalize(d.direction);
            break;
        case LightType::Quad: {
            Vec3 c = cross(d.edge1, d.edge2);
            l.area = length(c);
            l.normal = c / l.area;
            l.power = d.radiance * (kPi * l.area);
            break;
        }
        case LightType::Sun:
            l.sun = SunLight(d, bounds_min, bounds_max);
            l.desc.direction = l.sun.direction();
            l.power = l.sun.power();
            break;
        }
        // A sun's power is its irradiance times the scene's cross-section: it can overflow.
        if (!is_finite(l.power) || !std::isfinite(total_power_ + average(l.power)))
            throw InputError(scene.source + ": key 'lights[" + std::to_string(lights_.size()) +
                             "]': its power (emission times area) is too large for single precision");
        lights_.push_back(l);
        total_power_ += average(l.power);
        cdf_.push_back(total_power_);
    }
    // Emissive meshes: one light after the scene's own (index i < scene.lights.size() is
    // scene.lights[i]), sampled by power over its triangles.
    if (!emitters_.empty()) {
        Light l;
        l.mesh = true;
        l.power = emitters_.power();
        // Each material's emission is bounded, but not the area it covers.
        if (!is_finite(l.power) || !std::isfinite(total_power_ + average(l.power)))
            throw InputError(scene.source + ": the emissive triangles' power (emission times area) is too large "
                             "for single precision");
        lights_.push_back(l);
        total_power_ += average(l.power);
        cdf_.push_back(total_power_);
    }
    for (float& c : cdf_) c = total_power_ > 0 ? c / total_power_ : 0;
}

const LightSet::Light& LightSet::pick(float u, float& probability) const {
    size_t i = static_cast<size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin());
    i = std::min(i, lights_.size() - 1);
    while (i > 0 && cdf_[i] == cdf_[i - 1]) --i;  // never pick a light without power
    probability = cdf_[i] - (i > 0 ? cdf_[i - 1] : 0.0f);
    return lights_[i];
}

EmittedPhoton LightSet::emit(Rng& rng) const {
    float p = 1;
    const Light& l = pick(rng.uniform(), p);
    return emit_light(l, p, rng, nullptr);
}

EmittedPhoton LightSet::emit_from(size_t i, float a1, float a2, Rng& rng) const {
    const float pair[2] = {a1, a2};
    return emit_light(lights_[i], 1.0f, rng, pair);
}

bool LightSet::aimable(size_t i) const {
    const Light& l = lights_[i];
    return !l.mesh && l.desc.type != LightType::Laser;
}

// One photon of light l, chosen with probability p. Its aimed pair of uniforms (aimable()) is
// `pair` when given (unaimed), else two of rng's mapped through the light's aim, whose factor
// then scales the flux. The pair is drawn where the light drew those two before it had an aim
// (the first of the two first: a quad left their order to the compiler), so an empty aim leaves
// every photon as an unaimed light draws it.
EmittedPhoton LightSet::emit_light(const Light& l, float p, Rng& rng, const float* pair) const {
    auto aimed = [&](float& a1, float& a2) {
        if (pair) {
            a1 = pair[0];
            a2 = pair[1];
            return 1.0f;
        }
        const float u1 = rng.uniform(), u2 = rng.uniform();
        return l.aim.draw(u1, u2, a1, a2);
    };
    EmittedPhoton e;
    e.flux = l.power / p;
    e.direct_by_photons = false;
    if (l.mesh) {
        const float u1 = rng.uniform(), u2 = rng.uniform();
        const EmitterPoint ep = emitters_.sample(u1, u2);
        Vec3 n = ep.normal;
        float sides = 1;
        if (ep.two_sided) {
            sides = 2;
            if (rng.uniform() < 0.5f) n = -n;
        }
        // Flux of this path: L pi A_sides / (choice of this light) / (density of the point).
        e.flux = ep.radiance * (kPi * sides / (ep.pdf_area * p));
        e.origin = ep.position;
        e.direction = sample_cosine_hemisphere(n, rng.uniform(), rng.uniform());
        return e;
    }
    float a1 = 0, a2 = 0;
    switch (l.desc.type) {
    case LightType::Point:
        e.flux *= aimed(a1, a2);
        e.origin = l.desc.position;
        e.direction = sample_uniform_sphere(a1, a2);
        break;
    case LightType::Spot:
        e.flux *= aimed(a1, a2);
        e.origin = l.desc.position;
        e.direction = sample_uniform_cone(l.desc.direction, l.cos_cone, a1, a2);
        break;
    case LightType::Laser: {
        const float u1 = rng.uniform(), u2 = rng.uniform();
        float x, y;
        sample_disk(u1, u2, x, y);
        Vec3 t, b;
        make_basis(l.desc.direction, t, b);
        e.origin = l.desc.position + (t * x + b * y) * l.desc.radius;
        e.direction = l.desc.direction;
        e.direct_by_photons = true;
        break;
    }
    case LightType::Quad: {
        const float u1 = rng.uniform(), u2 = rng.uniform();
        e.origin = l.desc.corner + l.desc.edge1 * u1 + l.desc.edge2 * u2;
        e.flux *= aimed(a1, a2);
        e.direction = sample_cosine_hemisphere(l.normal, a1, a2);
        break;
    }
    case LightType::Sun: {
        e.flux *= aimed(a1, a2);
        const float u3 = rng.uniform(), u4 = rng.uniform();
        l.sun.emit(a1, a2, u3, u4, e.origin, e.direction, e.start_ns);
        break;
    }
    }
    return e;
}

bool LightSet::sample_direct(size_t i, Vec3 p, Vec3 n, float u1, float u2, DirectLightSample& out) const {
    const Light& l = lights_[i];
    out.pdf = 0;
    if (l.mesh) {
        const EmitterPoint ep = emitters_.sample(u1, u2);
        Vec3 v = ep.position - p;
        float d2 = dot(v, v);
        if (!(d2 > 0)) return false;
        float d = std::sqrt(d2);
        Vec3 wi = v / d;
        float cos_p = dot(n, wi), cos_l = -dot(ep.normal, wi);
        if (ep.two_sided) cos_l = std::abs(cos_l);
        if (cos_p <= 0 || cos_l <= 0) return false;
        out.irradiance = ep.radiance * (cos_l * cos_p / (d2 * ep.pdf_area));
        out.pdf = ep.pdf_area * d2 / cos_l;
        out.to_light = wi;
        out.distance = d;
        return true;
    }
    Vec3 target;
    switch (l.desc.type) {
    case LightType::Laser: return false;  // a collimated beam is reached by photons only
    case LightType::Sun:
        out.start_ns = 0;
        return l.sun.sample_direct(p, n, u1, u2, out.irradiance, out.to_light, out.distance, out.start_ns);
    case LightType::Point:
    case LightType::Spot: target = l.desc.position; break;
    case LightType::Quad: target = l.desc.corner + l.desc.edge1 * u1 + l.desc.edge2 * u2; break;
    }
    Vec3 v = target - p;
    float d2 = dot(v, v);
    if (!(d2 > 0)) return false;
    float d = std::sqrt(d2);
    Vec3 wi = v / d;
    float cos_p = dot(n, wi);
    if (cos_p <= 0) return false;
    if (l.desc.type == LightType::Quad) {
        float cos_l = -dot(l.normal, wi);
        if (cos_l <= 0) return false;
        out.irradiance = l.desc.radiance * (cos_l * cos_p * l.area / d2);
        out.pdf = d2 / (cos_l * l.area);
    } else {
        if (l.desc.type == LightType::Spot && dot(-wi, l.desc.direction) < l.cos_cone) return false;
        out.irradiance = l.intensity * (cos_p / d2);
    }
    out.to_light = wi;
    out.distance = d;
    return true;
}

bool LightSet::sample_in_medium(size_t i, float u1, float u2, InScatterLight& out, bool by_area) const {
    using Kind = InScatterLight::Kind;
    const Light& l = lights_[i];
    out = InScatterLight{};
    if (l.mesh) {
        const EmitterPoint ep = emitters_.sample(u1, u2);
        if (!(ep.pdf_area > 0)) return false;
        out.kind = ep.two_sided ? Kind::TwoSided : Kind::OneSided;
        out.position = ep.position;
        out.axis = ep.normal;
        out.emission = ep.radiance * (1 / ep.pdf_area);
        return true;
    }
    switch (l.desc.type) {
    case LightType::Laser: return false;
    case LightType::Point:
        out.kind = Kind::Isotropic;
        out.position = l.desc.position;
        out.emission = l.intensity;
        return true;
    case LightType::Spot:
        out.kind = Kind::Spot;
        out.position = l.desc.position;
        out.axis = l.desc.direction;
        out.cos_cone = l.cos_cone;
        out.emission = l.intensity;
        return true;
    case LightType::Quad:
        out.kind = Kind::OneSided;
        out.position = l.desc.corner + l.desc.edge1 * u1 + l.desc.edge2 * u2;
        out.axis = l.normal;
        out.emission = l.desc.radiance * l.area;
        // Edges at right angles (a rectangle): sampled by solid angle at each distance sample.
        if (!by_area && std::abs(dot(l.desc.edge1, l.desc.edge2)) <= 1e-5f * length(l.desc.edge1) * length(l.desc.edge2)) {
            out.rect = true;
            out.corner = l.desc.corner;
            out.edge1 = l.desc.edge1;
            out.edge2 = l.desc.edge2;
            out.radiance = l.desc.radiance;
        }
        return true;
    case LightType::Sun: {
        if (is_black(l.power)) return false;
        out.kind = Kind::Sun;
        l.sun.sample_in_medium(u1, u2, out.travel, out.sun_cos, out.emission);
        if (!(out.sun_cos > 0)) return false;
        out.axis = l.sun.direction();
        out.sun_h0 = l.sun.entry_offset();
        out.sun_lead = l.sun.lead();
        out.start_ns = -static_cast<double>(out.sun_lead) / (out.sun_cos * kSpeedOfLight);
        return true;
    }
    }
    return false;
}

double LightSet::latest_arrival_ns(size_t i, Vec3 p) const {
    const Light& l = lights_[i];
    if (l.mesh) return std::numeric_limits<double>::infinity();
    double far = 0;  // the farthest a sample of the light can be from p
    switch (l.desc.type) {
    case LightType::Laser:
    case LightType::Sun: return std::numeric_limits<double>::infinity();
    case LightType::Point:
    case LightType::Spot: far = length(l.desc.position - p); break;
    case LightType::Quad: far = length(l.desc.corner - p) + length(l.desc.edge1) + length(l.desc.edge2); break;
    }
    // (a margin for the float arithmetic of the sample's own distance)
    return far * (1 + 1e-4) / kSpeedOfLight;
}

}  // namespace sl
