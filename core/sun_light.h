#pragma once
// The sun: a directional light with a small angular diameter, given by the irradiance it makes
// on a plane facing it. `direction` is the way its light travels (from the sun into the scene).
//
// Photons leave a rectangle perpendicular to the direction that covers the scene's bounds
// projected along it (grown by the spread of the cone over the scene's depth), with directions
// inside the cone, cosine-weighted about its axis: the flux through the rectangle is exactly
// E x area. Direct light is one shadow ray along a direction sampled the same way.
//
// Time starts when the wavefront, a plane perpendicular to the direction, enters the scene's
// bounds: light reaches a point x at (dot(x, d) - h0) / c, h0 = min over the bounds' corners of
// dot(corner, d). The rectangle sits a little before that plane (so that a surface lying in the
// plane is still hit), and its light leaves it at a matching negative time.
#include <cmath>

#include "config/sun_desc.h"

namespace sl {

class SunLight {
public:
    SunLight() = default;
    // Bounds: the scene's (geometry and medium box); a flat or empty box emits nothing.
    SunLight(const LightDesc& desc, Vec3 bounds_min, Vec3 bounds_max);

    Vec3 power() const { return irradiance_ * area_; }  // W through the emitting rectangle
    Vec3 direction() const { return d_; }
    double entry_offset() const { return h0_; }          // dot(x, d) where the wavefront is at t = 0

    // A photon: origin on the rectangle (u1, u2), direction in the cone, and the time (ns, <= 0)
    // at which it leaves the origin. Four uniforms.
    void emit(float u1, float u2, float u3, float u4, Vec3& origin, Vec3& dir, double& start_ns) const;

    // One sample of the direct irradiance at p (unit normal n facing the viewer): the
    // irradiance estimate E cos(n, -w) / cos(d, w), the unit direction towards the sun, the
    // length of the shadow ray (to the emitting rectangle) and the time at which the light
    // left its start. False when the sampled direction is below the surface.
    bool sample_direct(Vec3 p, Vec3 n, float u1, float u2, Vec3& irradiance, Vec3& to_light, float& distance,
                       double& start_ns) const;

    // One sampled direction for in-scattering in the medium (no surface, so no cosine there):
    // the travel direction w, cos(w, axis), and the irradiance on a plane facing w, E / cos.
    // Light reaches x at max(0, dot(x, axis) - h0) / (cos c), after a shadow ray of
    // (max(0, dot(x, axis) - h0) + lead) / cos back to the rectangle.
    void sample_in_medium(float u1, float u2, Vec3& travel, float& cos_a, Vec3& irradiance) const;
    float lead() const { return lead_; }

private:
    Vec3 sample_direction(float u1, float u2) const;  // travel direction, pdf cos/(pi sin^2 a)

    Vec3 d_{0, -1, 0}, t_{1, 0, 0}, b_{0, 0, 1};  // direction and the rectangle's axes
    Vec3 irradiance_;
    float sin_half_ = 0;        // sine of the cone's half-angle
    double h0_ = 0;             // wavefront at t = 0: dot(x, d) = h0
    float lead_ = 0;            // the rectangle sits at dot(x, d) = h0 - lead
    float u0_ = 0, v0_ = 0, du_ = 0, dv_ = 0;  // the rectangle: t in [u0, u0+du], b in [v0, v0+dv]
    float area_ = 0;
};

}  // namespace sl
