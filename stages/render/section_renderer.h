#pragma once
// One convergence of a section: its passes, one after the other (a sequence, not a pipeline:
// pass i+1's photons are traced only once pass i's camera pass has gathered them):
//
//   for each pass: photon pass (batches in parallel, grid) -> camera pass (pixels in parallel)
//
// Each stage is parallel inside; the passes themselves never overlap.
// The photon pass traces the pass's photons into a grid (and, with a medium, the volume
// photons into a BVH); the camera pass then traces one path per pixel and gathers at its end:
// direct light, the beam estimate, the time-bucket scatter and the radius update. Gathering
// where the path ends keeps no visible points between the two stages: the only per-pixel
// memory of a section is its buffer.
#include <atomic>
#include <functional>
#include <memory>

#include "stages/render/camera_pass.h"
#include "stages/render/photon_map.h"
#include "stages/render/section_buffer.h"

namespace sl {

struct StageTimes {
    double camera_paths = 0, photons = 0, gather = 0;
    double volume = 0;      // the beam estimate (with a medium)
    double volume_cpu = 0;  // its share of the process CPU seconds
    double grid = 0;        // with ranks: sorting the exchanged photons into the grid (in `photons`)
};

// The live counters the passes add to (atomics, shared by the threads of a pass).
struct SectionCounters {
    CameraPassCounters camera;
    PhotonTraceCounters photons;
};

// What a section (or a whole render) counted, read once its passes are done.
struct RenderCounts {
    uint64_t photons = 0, photon_rays = 0, stored = 0, stored_volume = 0;
    uint64_t camera_rays = 0, beam_segments = 0, beam_hits = 0;  // beam: with a medium
    uint64_t rays() const { return photon_rays + camera_rays; }
    void add(const RenderCounts& o);
};

// Called after each pass with (passes done in this section).
using PassCallback = std::function<void(int)>;

struct SectionRun {
    std::unique_ptr<SectionBuffer> buffer;
    StageTimes times;
    uint64_t photon_map_bytes = 0;  // surface and volume photons
    RenderCounts counts;
};

// Renders passes until `passes` are done or `cancelled()` (asked before each pass) says stop.
// `resume_from`: the state to render into, fresh (a new SectionBuffer) or a checkpoint's (its
// passes_done passes are kept; the random streams of pass i depend only on the seed and i, so
// the result equals a render that never stopped). Null: a fresh buffer is made here.
// `abandon`, set during a pass, drops that pass while its photons are traced (within a batch):
// the buffer keeps the passes before it. Once the camera pass has begun, the pass finishes.
// A fresh buffer for this process's pixels (this rank's, with several), every pixel at its
// initial radius (ctx.gather_radii(), else ctx.initial_radius).
std::unique_ptr<SectionBuffer> new_section_buffer(const RenderContext& ctx, const SectionLayout& layout);

SectionRun render_section(const RenderContext& ctx, const SectionLayout& layout, int passes,
                          int64_t photons_per_pass, const PassCallback& on_pass = {}, const std::function<bool()>& cancelled = {},
                          std::unique_ptr<SectionBuffer> resume_from = nullptr,
                          const std::atomic<bool>* abandon = nullptr);

}  // namespace sl
