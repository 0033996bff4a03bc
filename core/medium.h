#pragma once
// A homogeneous participating medium in an axis-aligned box: RGB coefficients per meter,
// transmittance along a segment, free-flight sampling for photons and the Henyey-Greenstein
// phase function. Outside the box (and inside dielectric solids, by the renderer's choice)
// space is vacuum.
#include <cmath>

#include "foundation/constants.h"
#include "config/scene_desc.h"

namespace sl {

struct FreeFlight {
    float distance = 0;     // from the segment's start to the event (or the segment's length)
    bool scattered = false;  // an interaction before the segment's end
    Vec3 weight{1};          // throughput factor: Tr sigma_s / pdf at an event, Tr / P(pass) if not
};

class HomogeneousMedium {
public:
    // The box is the medium's bounds, or the scene's bounding box when it has none.
    HomogeneousMedium(const MediumDesc& desc, Vec3 scene_min, Vec3 scene_max);

    // Anything to compute at all: some extinction in a box of non-zero volume. A medium
    // without it is left out of the render entirely, so that it renders exactly as vacuum.
    bool active() const { return active_; }
    Vec3 sigma_t() const { return sigma_t_; }
    Vec3 sigma_s() const { return sigma_s_; }
    float g() const { return g_; }
    Vec3 box_min() const { return lo_; }
    Vec3 box_max() const { return hi_; }

    // The part [t0, t1] of o + t d, t in [tmin, tmax], inside the box; false when empty.
    bool clip(Vec3 o, Vec3 d, float tmin, float tmax, float& t0, float& t1) const;

    // e^(-sigma_t s) per channel for a length s inside the medium.
    Vec3 transmittance(float s) const {
        if (grey_) return Vec3(std::exp(-sigma_t_.x * s));
        return {std::exp(-sigma_t_.x * s), std::exp(-sigma_t_.y * s), std::exp(-sigma_t_.z * s)};
    }
    // Transmittance of the straight path o + t d, t in [0, tmax] (clipped to the box).
    Vec3 transmittance(Vec3 o, Vec3 d, float tmax) const {
        float t0, t1;
        return clip(o, d, 0, tmax, t0, t1) ? transmittance(t1 - t0) : Vec3(1);
    }

    // Samples the first interaction in a medium segment of the given length. A channel is
    // chosen uniformly and its exponential sampled; the weight divides by the pdf averaged
    // over the channels (one-sample MIS, balance heuristic), which keeps RGB coefficients that
    // differ, or are 0 in some channel, unbiased and the weights bounded by 3.
    FreeFlight sample_free_flight(float length, float u_channel, float u_distance) const;

    // Henyey-Greenstein, cos_theta between the propagation directions before and after.
    float phase(float cos_theta) const {
        float denom = 1 + g_ * g_ - 2 * g_ * cos_theta;
        return (1 - g_ * g_) * kInv4Pi / (denom * std::sqrt(denom));
    }
    // A new propagation direction for light travelling along unit wi, with pdf = phase.
    Vec3 sample_phase(Vec3 wi, float u1, float u2) const;

private:
    Vec3 sigma_t_, sigma_s_;
    float g_ = 0;
    Vec3 lo_, hi_;
    bool grey_ = true;
    bool active_ = false;
};

}  // namespace sl
