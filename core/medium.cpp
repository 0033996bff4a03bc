#include "core/medium.h"

#include <algorithm>

#include "core/sampling.h"

namespace sl {

HomogeneousMedium::HomogeneousMedium(const MediumDesc& desc, Vec3 scene_min, Vec3 scene_max)
    : sigma_t_(desc.sigma_a + desc.sigma_s), sigma_s_(desc.sigma_s), g_(desc.g),
      lo_(desc.has_bounds ? desc.bounds_min : scene_min), hi_(desc.has_bounds ? desc.bounds_max : scene_max) {
    grey_ = sigma_t_.x == sigma_t_.y && sigma_t_.y == sigma_t_.z;
    bool box = hi_.x > lo_.x && hi_.y > lo_.y && hi_.z > lo_.z;
    active_ = desc.present && box && max_component(sigma_t_) > 0 && is_finite(sigma_t_);
}

bool HomogeneousMedium::clip(Vec3 o, Vec3 d, float tmin, float tmax, float& t0, float& t1) const {
    t0 = tmin;
    t1 = tmax;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0) {  // parallel to the slab: inside it or never
            if (o[a] < lo_[a] || o[a] > hi_[a]) return false;
            continue;
        }
        float inv = 1 / d[a];
        float tn = (lo_[a] - o[a]) * inv, tf = (hi_[a] - o[a]) * inv;
        if (tn > tf) std::swap(tn, tf);
        t0 = std::max(t0, tn);
        t1 = std::min(t1, tf);
    }
    return t0 < t1;
}

FreeFlight HomogeneousMedium::sample_free_flight(float length, float u_channel, float u_distance) const {
    FreeFlight f;
    int c = std::min(static_cast<int>(u_channel * 3), 2);
    float st = sigma_t_[c];
    // -log(1 - u) with u < 1 is finite; a channel without extinction never interacts.
    float s = st > 0 ? -std::log1p(-u_distance) / st : INFINITY;
    if (s < length) {
        Vec3 tr = transmittance(s);
        float pdf = average(sigma_t_ * tr);  // > 0: channel c has sigma_t * tr > 0
        f.distance = s;
        f.scattered = true;
        f.weight = tr * sigma_s_ * (1 / pdf);
    } else {
        Vec3 tr = transmittance(length);
        float p = average(tr);  // >= tr[c] / 3, and tr[c] >= e^-16.7 whenever s >= length
        f.distance = length;
        f.weight = p > 0 ? tr * (1 / p) : Vec3(0);
    }
    return f;
}

Vec3 HomogeneousMedium::sample_phase(Vec3 wi, float u1, float u2) const {
    float cos_t;
    if (std::abs(g_) < 1e-3f) {
        cos_t = 1 - 2 * u1;
    } else {  // inverse of the HG CDF in cos_theta
        float sq = (1 - g_ * g_) / (1 - g_ + 2 * g_ * u1);
        cos_t = (1 + g_ * g_ - sq * sq) / (2 * g_);
    }
    cos_t = std::clamp(cos_t, -1.0f, 1.0f);
    float sin_t = std::sqrt(std::max(0.0f, 1 - cos_t * cos_t)), phi = 2 * kPi * u2;
    Vec3 t, b;
    make_basis(wi, t, b);
    return normalize(t * (sin_t * std::cos(phi)) + b * (sin_t * std::sin(phi)) + wi * cos_t);
}

}  // namespace sl
