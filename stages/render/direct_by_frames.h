#pragma once
// A quad light's direct light at a diffuse visible point, one sample per bucket (frame) its
// light arrives in (docs/medium.md, "A flash's direct light, frame by frame").
//
// The quad's light reaches the point over the spread of its distances, from its nearest point
// to its farthest: in a flash, often several frames. One point of the quad per pass lands its
// light in one of them, and each frame's share is a binomial count (cornell_haze_pulse's walls,
// max_depth 1, no haze: 38 % noise at 24 passes). Here each bucket of that spread gets a point
// drawn from the quad's band of distances that arrive in it (core/parallelogram_band.h) and its
// own shadow ray. Only with pulse emission: constant frames sum the buckets, and there it cost
// 1.2-1.3x the CPU of cornell_haze for no measurable gain; so a pulse retimed from a constant
// render's cube is noisier than a fresh pulse render (the same light on average). The bands are
// the timeline's buckets and their random numbers follow from the pixel's one pair and the
// band's times alone, so K sections, MPI ranks and timelines sharing edges deposit alike.
#include <cstddef>
#include <cstdint>

#include "foundation/vec3.h"
#include "stages/render/deposit_queue.h"
#include "stages/render/render_context.h"
#include "stages/render/section_buffer.h"

namespace sl {

// A spread of more frame widths than this (a large lamp and short frames): the caller takes its
// one sample of the whole quad instead, so the work per point stays bounded.
inline constexpr int64_t kMaxFrameBands = 64;

// Light `light` at the diffuse point p (origin: p lifted off its surface, nf its geometric and
// ns its shading normal, facing the viewer; back_ns the camera leg's time) with weight f (the
// BRDF times the camera path's throughput): adds each band's sample to the pixel's slots and
// counts the shadow rays in `rays`. Returns false, having added nothing, when the light is not a
// quad, or its light reaches p within one bucket or over more than kMaxFrameBands frame widths.
bool quad_direct_by_frames(const RenderContext& ctx, size_t light, Vec3 p, Vec3 origin, Vec3 nf, Vec3 ns, double back_ns,
                           float u1, float u2, Vec3 f, SectionBuffer& buffer, DepositQueue& deposits, size_t pixel,
                           uint64_t& rays);

}  // namespace sl
