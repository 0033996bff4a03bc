#pragma once
// What a render will hold in memory, known before anything is allocated: the time buckets of
// the sections in flight (the part that grows with frames and pixels, and the part K divides)
// and a fixed overhead (visible points, the photon map, frames on their way out, the encoder).
#include <cstdint>
#include <string>

#include "config/run_options.h"
#include "config/scene_desc.h"

namespace sl {

struct MemoryPlan {
    int sections = 1;
    bool overlap = false;                  // two sections alive: encode one, render the next
    uint64_t buffer_bytes_per_section = 0;  // the largest section's buckets and pixel state
    uint64_t fixed_overhead_bytes = 0;      // independent of K
    uint64_t bucket_budget = 0;             // what a memory budget left for buckets (0: none given)
    uint64_t buffers_in_flight() const { return buffer_bytes_per_section * (overlap ? 2 : 1); }
};

// With `ranks` MPI ranks, the buffers of one rank (the one with the most pixels).
uint64_t section_buffer_bytes(const SceneDesc& scene, int sections, int ranks = 1);
uint64_t fixed_overhead_bytes(const SceneDesc& scene);

// K from --sections, or the smallest K whose buffers fit the budget, or 1. The budget is
// --max-memory less the fixed part (the whole process stays within --max-memory), or
// --max-bucket-memory for the buckets alone; InputError with the number that would fit when
// even one frame per section is too much.
MemoryPlan plan_memory(const SceneDesc& scene, const RunOptions& options);

std::string format_bytes(uint64_t bytes);

}  // namespace sl
