#pragma once
// The camera half of a pass of stochastic progressive photon mapping, run after the photon
// pass: one jittered camera path per pixel, followed through mirrors and glass to its first
// diffuse surface (the visible point). There, at once and with their own arrival times: direct
// light, seen emitters and ambient; the beam estimate along the path's pieces in the medium;
// and the gather of the pass's photons with the pixel's shrinking radius. Visible points are
// never stored: per pixel, only the section buffer lives between passes. Each piece of the path
// inside the medium gathers its in-scattering as soon as it is found: single scattering by
// next-event estimation (single_scatter.h), the rest from the volume photons (beam_estimate.h).
#include <atomic>
#include <cstdint>

#include "stages/render/beam_estimate.h"
#include "stages/render/surface_gather.h"
#include "stages/render/photon_map.h"
#include "stages/render/render_context.h"
#include "stages/render/section_buffer.h"
#include "stages/render/volume_photon_map.h"

namespace sl {

struct CameraPassCounters {
    std::atomic<uint64_t> rays{0};
    std::atomic<uint64_t> beam_segments{0}, beam_hits{0};  // with a medium
    std::atomic<uint64_t> single_scatter_samples{0};        // distance samples of single scattering
};

// This pass's photons, already traced: the surface grid and, with a medium, the volume BVH.
struct PassPhotons {
    const PhotonMap& surface;
    const VolumePhotonMap* volume;  // null in vacuum
    int64_t emitted;                // photon paths traced this pass (the estimate's N)
};

// How the pass's time split between its parts (from per-pixel cycle counts), in seconds.
struct CameraPassTimes {
    double camera_paths = 0;  // camera paths, direct light, emitters
    double volume = 0;  // in-scattering: single scattering (next-event estimation) and the beam estimate
    double gather = 0;  // the surface gather and the radius update
    double volume_cpu = 0;  // the beam estimate's share of the process CPU time
};

// Runs the camera pass `pass` into `buffer` and finishes the pass: the largest radius for the
// next photon grid, the volume radius shrunk, passes_done counted.
CameraPassTimes camera_pass(const RenderContext& ctx, int pass, const PassPhotons& photons, SectionBuffer& buffer,
                            CameraPassCounters& counters);

}  // namespace sl
