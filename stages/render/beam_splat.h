#pragma once
// The beam estimate of the segments that leave the camera itself, from the photons' side. A
// segment's search of the volume BVH tests about nine photons for every one it takes (boxes
// grown by the widest radius, leaves of eight) and walks six nodes for each: most of the
// estimate's time. Here each photon is placed once a pass on the image, in the pixels whose
// rays may pass within its widest radius (PinholeCamera::pixels_near), and those pixels test
// it with the search's own test, unless every segment of their run of pixels ends before it
// (behind a wall): the same photons, the same kernel (BeamKernel), the same estimate.
// Segments after a mirror or glass still search the tree.
//
// Each pixel takes its photons in one order whatever the split of the image between threads,
// sections or ranks (the photons of its row's band in leaf order, then the wide ones), so
// those give the same images as one process.
#include <cstdint>
#include <span>
#include <vector>

#include "stages/render/beam_estimate.h"
#include "stages/render/camera_segments.h"
#include "stages/render/render_context.h"
#include "stages/render/section_buffer.h"
#include "stages/render/volume_photon_map.h"

namespace sl {

class BeamSplat {
public:
    // Places this pass's volume photons (the radius of buffer.volume_radius2) on the image.
    void build(const RenderContext& ctx, const VolumePhotonMap& photons, const SectionBuffer& buffer);

    // The beam estimate along the first segments of this rank's pixels [begin, end):
    // first[l - begin] is pixel l's (length 0: it has none), with `emitted` photon paths.
    void gather(const RenderContext& ctx, const VolumePhotonMap& photons, int64_t emitted, size_t begin,
                size_t end, std::span<const CameraSegment> first, SectionBuffer& buffer,
                BeamCounters& counters) const;

    // Bytes for `events` photons at most (pipeline/memory_plan.cpp): each photon's pixel box and
    // an entry in each band it spans (kMaxBands at most; wider ones are listed once).
    static uint64_t bytes_needed(uint64_t events) {
        return events * (sizeof(Box) + kMaxBands * sizeof(uint32_t));
    }

    static constexpr int kBandRows = 4;   // rows of the image a band holds
    static constexpr int kMaxBands = 4;   // a photon spanning more is listed once, as wide

private:
    struct Box {
        int32_t x0, x1, y0, y1;  // inclusive; y0 > y1: no pixel can take it
        float nearest;           // the least camera distance at which a ray may take it
    };
    std::vector<Box> box_;                  // per photon, in the tree's leaf order
    std::vector<uint32_t> band_start_;      // photons of band b: band_photons_[band_start_[b] ..]
    std::vector<uint32_t> band_photons_;
    std::vector<uint32_t> wide_;            // spanning more than kMaxBands bands
};

}  // namespace sl
