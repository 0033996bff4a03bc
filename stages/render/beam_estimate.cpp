#include "stages/render/beam_estimate.h"

#include <algorithm>

#include "core/sampling.h"

namespace sl {

void gather_volume_at(const RenderContext& ctx, const PixelSegments& segments, const VolumePhotonMap& photons,
                      int64_t photons_emitted, size_t pixel, SectionBuffer& buffer, BeamCounters& counters) {
    const HomogeneousMedium& medium = *ctx.medium;
    const Timeline& tl = ctx.timeline;
    const SectionLayout& layout = buffer.layout;
    const bool tof = ctx.scene.render.camera_tof;
    const double r2 = buffer.volume_radius2;
    const float k = static_cast<float>(1.0 / (static_cast<double>(std::max<int64_t>(photons_emitted, 1)) * kPi * r2));
    const float fr2 = static_cast<float>(r2);
    const float inv_c = static_cast<float>(1.0 / kSpeedOfLight);
    for (int j = 0; j < segments.count; ++j) {
        const CameraSegment& sg = segments.segment[j];
        const Vec3 w = sg.beta * k;  // K_r / N
        const double back0 = tof ? sg.camera_ns : 0.0;
        ++counters.segments;
        photons.for_each_along(sg.origin, sg.dir, sg.length, fr2, [&](uint32_t i, float s) {
            const VolumePhotonPayload& ph = photons.payload(i);
            if (ph.depth > sg.depth_left) return;
            ++counters.photon_hits;
            // The photon's light leaves towards the camera: against the segment.
            const float ph_fn = medium.phase(-dot(ph.dir, sg.dir));
            const Vec3 L = w * medium.transmittance(s) * ph.flux * ph_fn;
            const double t = ph.t_ns + (tof ? back0 + static_cast<double>(s * inv_c) : 0.0);
            const int slot = layout.slot_of_bucket(tl.bucket(t));
            if (slot < 0) return;
            float* acc = buffer.slot(pixel, slot);
            acc[0] += L.x;
            acc[1] += L.y;
            acc[2] += L.z;
        });
    }
}

}  // namespace sl
