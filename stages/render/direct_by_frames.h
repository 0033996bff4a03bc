#pragma once
// With a pulse, the direct light of a quad light at a diffuse visible point, one sample per
// frame it reaches (docs/medium.md, "Direct light of a flash, frame by frame").
//
// The quad's light reaches the point over the spread of its distances, from its nearest point
// to its farthest: in a flash, often several frames. One point of the quad per pass lands its
// light in one of them, and each frame's share is a binomial count (cornell_haze_pulse's walls,
// max_depth 1, no haze: 38 % noise at 24 passes). Here each bucket of that spread gets a point
// drawn from the quad's band of distances that arrive in it (core/parallelogram_band.h) and its
// own shadow ray. The bands come from the whole timeline's buckets and their random numbers from
// the pixel's one pair, so K sections and MPI ranks deposit what one process does.
#include <cstddef>
#include <cstdint>

#include "foundation/vec3.h"
#include "stages/render/deposit_queue.h"
#include "stages/render/render_context.h"
#include "stages/render/section_buffer.h"

namespace sl {

// More buckets than this in one point's spread (a large lamp and short frames): the caller takes
// its one sample of the whole quad instead, so the work per point stays bounded.
inline constexpr int64_t kMaxFrameBands = 64;

// Light `light` at the diffuse point p (origin: p lifted off its surface, nf its geometric and
// ns its shading normal, facing the viewer; back_ns the camera leg's time) with weight f (the
// BRDF times the camera path's throughput): adds each band's sample to the pixel's slots and
// counts the shadow rays in `rays`. Returns false, having added nothing, when the light is not a
// quad or its light reaches p within one bucket or more than kMaxFrameBands.
bool quad_direct_by_frames(const RenderContext& ctx, size_t light, Vec3 p, Vec3 origin, Vec3 nf, Vec3 ns, double back_ns,
                           float u1, float u2, Vec3 f, SectionBuffer& buffer, DepositQueue& deposits, size_t pixel,
                           uint64_t& rays);

}  // namespace sl
