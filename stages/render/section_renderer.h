#pragma once
// One convergence of a section, as a TBB flow graph over passes:
//
//   pass source -> limiter(1) -+-> camera pass (visible points, direct light) --+-> join -> gather
//                              +-> photon pass (batches in parallel) -> grid ---+      |
//                  ^-------------------------- next pass --------------------------------+
//
// The camera pass and the photon pass of a pass run side by side; the gather (the time-bucket
// scatter and the radius update) waits for both. With a medium the camera pass also records
// its segments in the medium, the photon pass builds the volume photons' BVH, and the gather
// first runs the beam radiance estimate.
#include <functional>
#include <memory>

#include "stages/render/beam_estimate.h"
#include "stages/render/photon_map.h"
#include "stages/render/section_buffer.h"
#include "stages/render/visible_points.h"

namespace sl {

struct StageTimes {
    double camera = 0, photons = 0, gather = 0;
    double volume = 0;      // the beam estimate's part of `gather` (with a medium)
    double volume_cpu = 0;  // its process CPU seconds (nothing else of ours runs meanwhile)
};

struct SectionCounters {
    CameraPassCounters camera;
    PhotonTraceCounters photons;
    std::atomic<uint64_t> beam_segments{0}, beam_hits{0};  // with a medium
};

// Called after each pass with (passes done in this section).
using PassCallback = std::function<void(int)>;

struct SectionRun {
    std::unique_ptr<SectionBuffer> buffer;
    StageTimes times;
    uint64_t photon_map_bytes = 0;  // surface and volume photons, camera segments
};

SectionRun render_section(const RenderContext& ctx, const SectionLayout& layout, int passes,
                          int64_t photons_per_pass, SectionCounters& counters,
                          const PassCallback& on_pass = {}, const std::function<bool()>& cancelled = {});

}  // namespace sl
