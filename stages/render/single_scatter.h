#pragma once
// Single scattering (light -> one point in the medium -> camera) by next-event estimation along
// one camera segment inside the medium, time-resolved (docs/medium.md, "Single scattering").
//
// Per light, one light sample (a point on it, or a sun direction) is kept for the whole segment,
// so that the arrival time T(t) of its light scattered at distance t is known in closed form and
// is monotone on at most two pieces of the segment. Each time stratum (a bucket of the timeline,
// or the stretches before and after it) then maps to at most one interval of each piece, and one
// distance is sampled in each (equiangular about the light's point; truncated exponential for
// the sun), with one shadow ray: every frame the light reaches gets its own sample, and frames it
// cannot reach get nothing. The strata are the whole timeline's, not the section's, and their
// random numbers come from one uniform per segment and light, so that K sections and MPI ranks
// deposit into each bucket exactly what one process does. A rectangular quad light is evaluated
// at each distance sample by a fresh point uniform in its solid angle (core/spherical_rectangle.h).
#include <cstdint>

#include "core/rng.h"
#include "stages/render/camera_segments.h"
#include "stages/render/deposit_queue.h"
#include "stages/render/render_context.h"
#include "stages/render/section_buffer.h"

namespace sl {

struct SingleScatterCounters {
    uint64_t samples = 0;      // distance samples (strata) evaluated
    uint64_t shadow_rays = 0;  // of which traced against the geometry
};

// More strata than this along one segment and one light are merged in groups of whole
// buckets (a sample then goes to the bucket its own time falls in): the work per segment is
// bounded by kMaxStrata distance samples and shadow rays per light and piece.
inline constexpr int kMaxStrata = 64;

// Adds the single-scattering estimate along `sg` (pixel `pixel`'s throughput sg.beta included)
// to the pixel's slots through `deposits`. Draws exactly 5 uniforms per light from `rng`.
void single_scatter_along(const RenderContext& ctx, const CameraSegment& sg, Rng& rng, SectionBuffer& buffer,
                          DepositQueue& deposits, size_t pixel, SingleScatterCounters& counters);

}  // namespace sl
