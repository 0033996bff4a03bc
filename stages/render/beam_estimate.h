#pragma once
// The beam radiance estimate with photon points: every camera segment that crosses the
// medium collects this pass's volume photons within the volume radius r(s) of it (the pass's
// radius, or a pixel footprint at that distance when that is wider: see kFootprintRadii),
//
//   L += beta K_r Phi_i p(theta_i) Tr(s_i) / N,   K_r = 1 / (pi r(s_i)^2),
//
// into the slot of each photon's arrival time (plus the camera leg with camera_tof). Like the
// surface gather, each pixel is gathered by the thread that traced it, in a fixed order. The
// radius shrinks after every pass: r^2_(i+1) = r^2_i (i + alpha) / (i + 1).
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/sampling.h"
#include "stages/render/camera_segments.h"
#include "stages/render/render_context.h"
#include "stages/render/section_buffer.h"
#include "stages/render/volume_photon_map.h"

namespace sl {

struct BeamCounters {
    uint64_t segments = 0;     // camera segments queried
    uint64_t photon_hits = 0;  // photons gathered
};

// The pass's kernel, written once for the search along a segment (gather_volume_at) and the
// photons' side of it (beam_splat.h): the radius along a segment, and what a photon taken adds.
class BeamKernel {
public:
    BeamKernel(const RenderContext& ctx, const SectionBuffer& buffer, int64_t photons_emitted);

    float r0() const { return r0_; }
    float slope() const { return slope_; }
    // The radius's offset for a segment: its floor grows with the camera leg before it.
    float s0(const CameraSegment& sg) const { return slope_ * static_cast<float>(sg.camera_ns * kSpeedOfLight); }
    // The widest radius a photon at distance `from_camera` (along the path) can be taken with.
    float widest(float from_camera) const { return std::max(r0_, slope_ * from_camera); }

    // Adds photon ph, taken at s with the squared radius q, to the pixel's slots.
    void add(const CameraSegment& sg, const VolumePhotonPayload& ph, float s, float q, size_t pixel,
             SectionBuffer& buffer, BeamCounters& counters) const {
        if (ph.depth > sg.depth_left) return;
        ++counters.photon_hits;
        // The photon's light leaves towards the camera: against the segment. The kernel is
        // normalised at the photon's own radius: K = 1 / (pi r(s)^2).
        const float ph_fn = medium_.phase(-dot(ph.dir, sg.dir));
        const float k = static_cast<float>(n_inv_ / (kPi * static_cast<double>(q)));
        const Vec3 L = sg.beta * (k * ph_fn) * medium_.transmittance(s) * ph.flux;
        const double t = ph.t_ns + (tof_ ? sg.camera_ns + static_cast<double>(s * inv_c_) : 0.0);
        const int slot = buffer.layout.slot_of_bucket(bucket_(t));
        if (slot < 0) return;
        float* acc = buffer.slot(pixel, slot);
        acc[0] += L.x;
        acc[1] += L.y;
        acc[2] += L.z;
    }

private:
    const HomogeneousMedium& medium_;
    BucketFinder bucket_;
    bool tof_;
    double n_inv_;
    float r0_, slope_;
    float inv_c_ = static_cast<float>(1.0 / kSpeedOfLight);
};

// Adds the estimate along one of a pixel's segments to its slots, with this pass's volume radius
// (buffer.volume_radius2) and `photons_emitted` photon paths.
void gather_volume_at(const RenderContext& ctx, const CameraSegment& sg, const VolumePhotonMap& photons,
                      int64_t photons_emitted, size_t pixel, SectionBuffer& buffer, BeamCounters& counters);

// The beam's radius never falls below kFootprintRadii pixel footprints at the photon's distance
// from the camera (along the path), times sqrt(r_i / r_0): where the pixels' rays lie further
// apart than the radius, most photons fall between them and the few gathered weigh
// 1 / (pi r^2) each, which makes the image noisy and moves its mean from seed to seed. The
// floor shrinks more slowly than the radius but still to 0 (as i^((alpha-1)/4)), so the estimate
// stays consistent; each photon's kernel is normalised at its own radius, 1 / (pi r(s)^2).
// Near the camera the radius stays r_i (a cylinder): a kernel that narrowed there with the
// footprint would give a photon at distance s a weight growing as 1/s^2 in every pixel it
// touches, an error without bound.
inline constexpr float kFootprintRadii = 1.0f;

// The volume radius schedule's factor after pass i (0-based): r^2_(i+1) / r^2_i.
inline double volume_radius_shrink(int pass, double alpha) { return (pass + alpha) / (pass + 1.0); }

}  // namespace sl
