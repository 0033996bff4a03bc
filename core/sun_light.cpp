#include "core/sun_light.h"

#include <algorithm>
#include <cmath>

#include "core/sampling.h"
#include "foundation/constants.h"

namespace sl {

SunLight::SunLight(const LightDesc& desc, Vec3 lo, Vec3 hi) {
    d_ = normalize(desc.direction);
    make_basis(d_, t_, b_);
    irradiance_ = desc.irradiance;
    const double half = 0.5 * desc.angle_deg * kPiDouble / 180.0;
    sin_half_ = static_cast<float>(std::sin(half));
    if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) return;  // no bounds: no light
    // The bounds' corners along the direction and across it.
    double hmin = 1e300, hmax = -1e300, umin = 1e300, umax = -1e300, vmin = 1e300, vmax = -1e300;
    for (int c = 0; c < 8; ++c) {
        const Vec3 p{(c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z};
        const double h = dot(p, d_), u = dot(p, t_), v = dot(p, b_);
        hmin = std::min(hmin, h); hmax = std::max(hmax, h);
        umin = std::min(umin, u); umax = std::max(umax, u);
        vmin = std::min(vmin, v); vmax = std::max(vmax, v);
    }
    const double diag = length(hi - lo);
    h0_ = hmin;
    lead_ = static_cast<float>(1e-3 * diag + 1e-6);
    // Directions tilt by up to the half-angle: over the depth (plus the lead) a photon that
    // reaches the bounds may start that much further out.
    const double margin = (hmax - hmin + lead_) * std::tan(half) + 1e-6 * diag;
    u0_ = static_cast<float>(umin - margin);
    v0_ = static_cast<float>(vmin - margin);
    du_ = static_cast<float>(umax - umin + 2 * margin);
    dv_ = static_cast<float>(vmax - vmin + 2 * margin);
    area_ = du_ * dv_;
    if (!(umax > umin && vmax > vmin)) area_ = 0;  // a box seen edge-on: nothing to light
}

Vec3 SunLight::sample_direction(float u1, float u2) const {
    // Cosine-weighted inside the cone: a uniform point on the disc of radius sin(a), lifted.
    float x, y;
    sample_disk(u1, u2, x, y);
    x *= sin_half_;
    y *= sin_half_;
    const float z = std::sqrt(std::max(0.0f, 1 - x * x - y * y));
    return normalize(t_ * x + b_ * y + d_ * z);
}

void SunLight::emit(float u1, float u2, float u3, float u4, Vec3& origin, Vec3& dir, double& start_ns) const {
    const float u = u0_ + du_ * u1, v = v0_ + dv_ * u2;
    origin = t_ * u + b_ * v + d_ * static_cast<float>(h0_ - lead_);
    dir = sample_direction(u3, u4);
    // The wavefront (perpendicular to d) is at dot(x, d) = h0 at t = 0: lead before it, earlier.
    start_ns = -static_cast<double>(lead_) / (dot(dir, d_) * kSpeedOfLight);
}

bool SunLight::sample_direct(Vec3 p, Vec3 n, float u1, float u2, Vec3& irradiance, Vec3& to_light, float& distance,
                             double& start_ns) const {
    const Vec3 w = sample_direction(u1, u2);
    const float cos_p = -dot(n, w);
    if (cos_p <= 0) return false;
    const float cos_a = dot(w, d_);
    // E(x) = integral over the cone of L cos_p; with pdf cos_a / (pi sin^2 a) and E = L pi sin^2 a
    // one sample is E cos_p / cos_a.
    irradiance = irradiance_ * (cos_p / cos_a);
    to_light = -w;
    // Back to the rectangle, which lies lead before the t = 0 plane.
    const double along = std::max(0.0, dot(p, d_) - h0_) + lead_;
    distance = static_cast<float>(along / cos_a);
    start_ns = -static_cast<double>(lead_) / (cos_a * kSpeedOfLight);
    return true;
}

void SunLight::sample_in_medium(float u1, float u2, Vec3& travel, float& cos_a, Vec3& irradiance) const {
    travel = sample_direction(u1, u2);
    cos_a = dot(travel, d_);
    irradiance = irradiance_ * (1 / cos_a);  // sample_direct's E cos_p / cos_a with cos_p = 1
}

}  // namespace sl
