#include "stages/render/beam_estimate.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>

#include "core/sampling.h"

namespace sl {

BeamCounters gather_volume(const RenderContext& ctx, const CameraSegments& segments,
                           const VolumePhotonMap& photons, int64_t photons_per_pass, SectionBuffer& buffer) {
    const HomogeneousMedium& medium = *ctx.medium;
    const Timeline& tl = ctx.timeline;
    const SectionLayout& layout = buffer.layout;
    const bool tof = ctx.scene.render.camera_tof;
    const double r2 = buffer.volume_radius2;
    const float k = static_cast<float>(1.0 / (static_cast<double>(std::max<int64_t>(photons_per_pass, 1)) * kPi * r2));
    const float fr2 = static_cast<float>(r2);
    const float inv_c = static_cast<float>(1.0 / kSpeedOfLight);

    BeamCounters total = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, segments.pixels(), 256), BeamCounters{},
        [&](const tbb::blocked_range<size_t>& r, BeamCounters c) {
            for (size_t p = r.begin(); p != r.end(); ++p) {
                const CameraSegment* seg = segments.of(p);
                for (int j = 0, n = segments.count[p]; j < n; ++j) {
                    const CameraSegment& sg = seg[j];
                    const Vec3 w = sg.beta * k;  // K_r / N
                    const double back0 = tof ? sg.camera_ns : 0.0;
                    ++c.segments;
                    photons.for_each_along(sg.origin, sg.dir, sg.length, fr2, [&](uint32_t i, float s) {
                        const VolumePhotonPayload& ph = photons.payload(i);
                        if (ph.depth > sg.depth_left) return;
                        ++c.photon_hits;
                        // The photon's light leaves towards the camera: against the segment.
                        const float ph_fn = medium.phase(-dot(ph.dir, sg.dir));
                        const Vec3 L = w * medium.transmittance(s) * ph.flux * ph_fn;
                        const double t = ph.t_ns + (tof ? back0 + static_cast<double>(s * inv_c) : 0.0);
                        float* acc = buffer.slot(p, layout.slot_of_bucket(tl.bucket(t)));
                        acc[0] += L.x;
                        acc[1] += L.y;
                        acc[2] += L.z;
                    });
                }
            }
            return c;
        },
        [](BeamCounters a, BeamCounters b) { return BeamCounters{a.segments + b.segments, a.photon_hits + b.photon_hits}; });
    buffer.volume_radius2 *= volume_radius_shrink(buffer.passes_done, ctx.scene.render.alpha);
    return total;
}

}  // namespace sl
