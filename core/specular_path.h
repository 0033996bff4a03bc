#pragma once
// One specular event on a camera or photon path, with the bookkeeping both kinds of path need:
// the new direction, the new origin nudged off the surface to the side the path leaves by, and
// whether the path now travels inside a dielectric (and that dielectric's index, which slows
// the light on the next leg).
#include "core/scattering.h"
#include "core/scene_geometry.h"

namespace sl {

// Returns the throughput weight of the event; updates o, d, inside and inside_ior.
inline Vec3 follow_specular(const SurfaceMaterial& m, const SurfaceHit& hit, Vec3& o, Vec3& d, bool& inside,
                            float& inside_ior, Rng& rng) {
    const SpecularBounce b = specular_bounce(m, d, hit.normal, inside, rng);
    if (b.inside_after != inside) inside_ior = m.ior;
    inside = b.inside_after;
    const Vec3 side = dot(b.direction, hit.normal) > 0 ? hit.normal : -hit.normal;
    o = hit.position + side * ray_epsilon(hit.position, hit.t);
    d = b.direction;
    return b.weight;
}

}  // namespace sl
