#include "stages/render/beam_estimate.h"

#include <algorithm>
#include <cmath>

#include "core/sampling.h"

namespace sl {

void gather_volume_at(const RenderContext& ctx, const CameraSegment& sg, const VolumePhotonMap& photons,
                      int64_t photons_emitted, size_t pixel, SectionBuffer& buffer, BeamCounters& counters) {
    const HomogeneousMedium& medium = *ctx.medium;
    const BucketFinder bucket(ctx.timeline);  // every photon along the segments asks it
    const SectionLayout& layout = buffer.layout;
    const bool tof = ctx.render.camera_tof;
    const double r2 = buffer.volume_radius2;
    const double n_inv = 1.0 / static_cast<double>(std::max<int64_t>(photons_emitted, 1));
    // The radius this pass; the pixel-footprint floor shrinks as the square root of its shrink.
    const float r = static_cast<float>(std::sqrt(r2));
    const float scale = ctx.volume_radius > 0 ? r / ctx.volume_radius : 1.0f;
    const float slope = std::sqrt(scale) * kFootprintRadii * ctx.camera.pixel_footprint(1.0f);
    const float inv_c = static_cast<float>(1.0 / kSpeedOfLight);
    {
        const double back0 = tof ? sg.camera_ns : 0.0;
        const float s0 = slope * static_cast<float>(sg.camera_ns * kSpeedOfLight);  // the camera leg so far
        ++counters.segments;
        photons.for_each_along_cone(sg.origin, sg.dir, sg.length, r, s0, slope, [&](uint32_t i, float s, float q) {
            const VolumePhotonPayload& ph = photons.payload(i);
            if (ph.depth > sg.depth_left) return;
            ++counters.photon_hits;
            // The photon's light leaves towards the camera: against the segment. The kernel is
            // normalised at the photon's own radius: K = 1 / (pi r(s)^2).
            const float ph_fn = medium.phase(-dot(ph.dir, sg.dir));
            const float k = static_cast<float>(n_inv / (kPi * static_cast<double>(q)));
            const Vec3 L = sg.beta * (k * ph_fn) * medium.transmittance(s) * ph.flux;
            const double t = ph.t_ns + (tof ? back0 + static_cast<double>(s * inv_c) : 0.0);
            const int slot = layout.slot_of_bucket(bucket(t));
            if (slot < 0) return;
            float* acc = buffer.slot(pixel, slot);
            acc[0] += L.x;
            acc[1] += L.y;
            acc[2] += L.z;
        });
    }
}

}  // namespace sl
