#pragma once
// What a render will hold in memory, known before anything is allocated: the time buckets of
// the sections in flight (the part that grows with frames and pixels, and the part K divides)
// and a fixed part (the program, the scene, the photon map, frames on their way out, the
// encoder). Every figure is computed from the scene and the options alone, never read from the
// running process: the same scene and flags give the same K on every run.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "config/run_options.h"
#include "config/scene_desc.h"
#include "foundation/byte_sizes.h"  // format_bytes, for the plan's users

namespace sl {

// The fixed part, term by term (independent of K). `slowlight info` prints each.
struct MemoryBaseline {
    uint64_t program = 0;         // code, libraries and start-up heap: a measured constant
    uint64_t scene = 0;           // imported meshes, Embree's copy and BVH, textures
    uint64_t photon_map = 0;      // one pass's surface photons (PhotonMap::bytes_needed)
    uint64_t volume_photons = 0;  // one pass's medium events (VolumePhotonMap::bytes_needed)
    uint64_t frames = 0;          // frames on their way out: the running sum, float and 8-bit frames
    uint64_t encoder = 0;         // the codec: its library state, its own frames, our staged frames
    uint64_t gather_radii = 0;    // each pixel's initial radius, cut or star (automatic radius; edge_radius.h)
    // What the photon terms were computed from: stored records and medium events per photon
    // path, counted on a fixed-seed pilot of the scene's own lights (PhotonMap::trace).
    double records_per_path = 0, volume_events_per_path = 0;
    uint64_t total() const {
        return program + scene + photon_map + volume_photons + frames + encoder + gather_radii;
    }
    // (name, bytes) in the order above, for printing.
    std::vector<std::pair<const char*, uint64_t>> terms() const;
};

struct MemoryPlan {
    int sections = 1;
    bool overlap = false;                  // two sections alive: encode one, render the next
    uint64_t buffer_bytes_per_section = 0;  // the largest section's buckets
    uint64_t fixed_overhead_bytes = 0;      // fixed.total(): independent of K
    uint64_t bucket_budget = 0;             // what a memory budget left for buckets (0: none given)
    MemoryBaseline fixed;
    uint64_t buffers_in_flight() const { return buffer_bytes_per_section * (overlap ? 2 : 1); }
    uint64_t total() const { return fixed_overhead_bytes + buffers_in_flight(); }
};

// With `ranks` MPI ranks, the buffers of one rank (the one with the most pixels).
uint64_t section_buffer_bytes(const SceneDesc& scene, int sections, int ranks = 1);
// The fixed part for these outputs (the encoder depends on the video container). Builds the
// scene's geometry once to count a pilot's photon records; compute it once and pass it on.
MemoryBaseline memory_baseline(const SceneDesc& scene, const RunOptions& options);

// K from --sections, or the smallest K whose buffers fit the budget, or 1. The budget is
// --max-memory less the fixed part (the whole process stays within --max-memory), or
// --max-bucket-memory for the buckets alone; InputError with the number that would fit when
// even one frame per section is too much.
MemoryPlan plan_memory(const SceneDesc& scene, const RunOptions& options);
MemoryPlan plan_memory(const SceneDesc& scene, const RunOptions& options, const MemoryBaseline& fixed);

}  // namespace sl
