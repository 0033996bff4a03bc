#include "stages/render/beam_estimate.h"

namespace sl {

BeamKernel::BeamKernel(const RenderContext& ctx, const SectionBuffer& buffer, int64_t photons_emitted)
    : medium_(*ctx.medium),
      bucket_(ctx.timeline),
      tof_(ctx.render.camera_tof),
      n_inv_(1.0 / static_cast<double>(std::max<int64_t>(photons_emitted, 1))) {
    // The radius this pass; the pixel-footprint floor shrinks as the square root of its shrink.
    const double r2 = buffer.volume_radius2;
    r0_ = static_cast<float>(std::sqrt(r2));
    const float scale = ctx.volume_radius > 0 ? r0_ / ctx.volume_radius : 1.0f;
    slope_ = std::sqrt(scale) * kFootprintRadii * ctx.camera.pixel_footprint(1.0f);
}

void gather_volume_at(const RenderContext& ctx, const CameraSegment& sg, const VolumePhotonMap& photons,
                      int64_t photons_emitted, size_t pixel, SectionBuffer& buffer, BeamCounters& counters) {
    const BeamKernel kernel(ctx, buffer, photons_emitted);
    ++counters.segments;
    photons.for_each_along_cone(sg.origin, sg.dir, sg.length, kernel.r0(), kernel.s0(sg), kernel.slope(),
                                [&](uint32_t i, float s, float q) {
                                    kernel.add(sg, photons.payload(i), s, q, pixel, buffer, counters);
                                });
}

}  // namespace sl
