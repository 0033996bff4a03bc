#pragma once
// The time-bucket scatter: every visible point collects the pass's photons within its radius
// into the slot of each photon's arrival time, then shrinks its radius (progressive photon
// mapping's N' = N + alpha M, R'^2 = R^2 (N + alpha M) / (N + M)). Work is per pixel, so each
// pixel's slots are written by one thread in a fixed order: no atomics, repeatable sums.
#include <cstdint>

#include "stages/render/photon_map.h"
#include "stages/render/section_buffer.h"
#include "stages/render/visible_points.h"

namespace sl {

void gather_photons(const RenderContext& ctx, const VisiblePoints& vps, const PhotonMap& photons,
                    int64_t photons_per_pass, SectionBuffer& buffer);

}  // namespace sl
