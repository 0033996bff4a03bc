#pragma once
// The time-bucket scatter at one visible point: it collects the pass's photons within its
// pixel's radius into the slot of each photon's arrival time, then shrinks the radius
// (progressive photon mapping's N' = N + alpha M, R'^2 = R^2 (N + alpha M) / (N + M)). Each
// pixel is gathered by the thread that traced it, in a fixed order: no atomics, repeatable sums.
#include <cstdint>

#include "core/bsdf/bsdf.h"
#include "foundation/vec3.h"
#include "stages/render/deposit_queue.h"
#include "stages/render/photon_map.h"
#include "stages/render/render_context.h"
#include "stages/render/section_buffer.h"

namespace sl {

// Where a camera path ends on a diffuse surface, or on a GGX surface that gathers
// (core/material_table.h, GlossyUse::Gather). Visible points live only while their pixel is
// gathered (one per thread), so the GGX ones keep the BSDF and wo whole rather than packed.
struct VisiblePoint {
    Vec3 position;
    Vec3 normal;         // unit shading normal, facing the camera path
    Vec3 weight;         // Lambertian: camera throughput x BRDF (albedo / pi); GGX: the throughput
    double camera_ns;    // time back to the camera (with camera_tof; else 0)
    uint32_t depth_left;  // photon vertices this point may still accept
    bool glossy = false;  // a GGX point: each photon weighs f(wo, its incoming direction)
    bsdf::Bsdf bsdf;      // GGX: the BSDF at the point (textures applied)
    Vec3 wo;              // GGX: unit, towards the camera
    Vec3 bsdf_normal;     // GGX: the BSDF frame's +z, `normal` with the material's normal map
    // The point's share of its pixel's pass: 1, or 1/n for each of the n branches of a camera
    // path split at a glossy vertex (its weight already carries it); the photons it finds
    // count by it in the radius's statistics, so that a split pixel's radius shrinks as one
    // path's would.
    float share = 1;
};

// Adds `photons`' estimate at `vp` to pixel `pixel` of `buffer` (flux / (pi R^2 emitted)), through
// `deposits` (the additions may still be queued on return), and shrinks the pixel's radius.
// Returns the number of photons found.
uint32_t gather_surface_at(const RenderContext& ctx, const VisiblePoint& vp, const PhotonMap& photons,
                           int64_t photons_emitted, size_t pixel, SectionBuffer& buffer, DepositQueue& deposits);

}  // namespace sl
