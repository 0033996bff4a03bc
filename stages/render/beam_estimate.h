#pragma once
// The beam radiance estimate with photon points: every camera segment that crosses the
// medium collects this pass's volume photons within the volume radius r of it,
//
//   L += beta K_r Phi_i p(theta_i) Tr(s_i) / N,   K_r = 1 / (pi r^2),
//
// into the slot of each photon's arrival time (plus the camera leg with camera_tof). Like the
// surface gather, work is per pixel: each pixel's slots are written by one thread in a fixed
// order. Then r shrinks for the next pass: r^2_(i+1) = r^2_i (i + alpha) / (i + 1).
#include <cstdint>

#include "stages/render/camera_segments.h"
#include "stages/render/render_context.h"
#include "stages/render/section_buffer.h"
#include "stages/render/volume_photons.h"

namespace sl {

struct BeamCounters {
    uint64_t segments = 0;     // camera segments queried
    uint64_t photon_hits = 0;  // photons gathered
};

// Adds this pass's volume estimate to `buffer` and shrinks buffer.volume_radius2. Call it
// before gather_photons (which counts the pass as done).
BeamCounters gather_volume(const RenderContext& ctx, const CameraSegments& segments,
                           const VolumePhotonMap& photons, int64_t photons_per_pass, SectionBuffer& buffer);

// The volume radius schedule's factor after pass i (0-based): r^2_(i+1) / r^2_i.
inline double volume_radius_shrink(int pass, double alpha) { return (pass + alpha) / (pass + 1.0); }

}  // namespace sl
