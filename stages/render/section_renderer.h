#pragma once
// One convergence of a section, as a TBB flow graph over passes:
//
//   pass source -> limiter(1) -+-> camera pass (visible points, direct light) --+-> join -> gather
//                              +-> photon pass (batches in parallel) -> grid ---+      |
//                  ^-------------------------- next pass --------------------------------+
//
// The camera pass and the photon pass of a pass run side by side; the gather (the time-bucket
// scatter and the radius update) waits for both.
#include <functional>
#include <memory>

#include "stages/render/photon_map.h"
#include "stages/render/section_buffer.h"
#include "stages/render/visible_points.h"

namespace sl {

struct StageTimes {
    double camera = 0, photons = 0, gather = 0;
};

struct SectionCounters {
    CameraPassCounters camera;
    PhotonTraceCounters photons;
};

// Called after each pass with (passes done in this section).
using PassCallback = std::function<void(int)>;

struct SectionRun {
    std::unique_ptr<SectionBuffer> buffer;
    StageTimes times;
    uint64_t photon_map_bytes = 0;
};

SectionRun render_section(const RenderContext& ctx, const SectionLayout& layout, int passes,
                          int64_t photons_per_pass, SectionCounters& counters,
                          const PassCallback& on_pass = {}, const std::function<bool()>& cancelled = {});

}  // namespace sl
