#pragma once
// The Embree ceiling both benchmarks compare the photon pass with: random rays through the
// scene's BVH (origins uniform in its bounding box, directions uniform), in parallel batches
// with their own random streams, as the photon pass runs its own.
#include <tbb/parallel_for.h>

#include <atomic>
#include <cstdint>

#include "core/rng.h"
#include "core/sampling.h"
#include "stages/render/render_context.h"

namespace sl::bench {

// Traces batches x per_batch rays (stream `round` of seed 7); returns how many hit something.
inline uint64_t trace_random_rays(const RenderContext& ctx, size_t batches, size_t per_batch, uint64_t round) {
    const Vec3 lo = ctx.geometry.bounds_min(), hi = ctx.geometry.bounds_max();
    std::atomic<uint64_t> hits{0};
    tbb::parallel_for(size_t(0), batches, [&](size_t b) {
        Rng rng(7, 3, round, b);
        uint64_t h = 0;
        for (size_t i = 0; i < per_batch; ++i) {
            Vec3 o{lo.x + (hi.x - lo.x) * rng.uniform(), lo.y + (hi.y - lo.y) * rng.uniform(),
                   lo.z + (hi.z - lo.z) * rng.uniform()};
            Vec3 d = sample_uniform_sphere(rng.uniform(), rng.uniform());
            SurfaceHit hit;
            h += ctx.geometry.intersect(o, d, 0, 1e30f, hit);
        }
        hits += h;
    });
    return hits.load();
}

}  // namespace sl::bench
