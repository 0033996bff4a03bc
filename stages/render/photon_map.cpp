#include "stages/render/photon_map.h"

#include <tbb/parallel_for.h>

#include <algorithm>

#include "core/rng.h"
#include "core/scattering.h"

namespace sl {
namespace {

// Follows one photon path, storing a record at every diffuse vertex whose light is not
// already computed as direct light (vertex 1 is direct, except for lasers).
struct PhotonPath {
    const RenderContext& ctx;
    const SectionLayout& layout;
    std::vector<PhotonRecord>& out;
    uint64_t rays = 0;

    void trace(Rng& rng) {
        const SceneDesc& sc = ctx.scene;
        const int max_depth = sc.render.max_depth;
        EmittedPhoton e = ctx.lights.emit(rng);
        Vec3 o = e.origin, d = e.direction, flux = e.flux;
        double t = 0;
        bool inside = false;
        float inside_ior = 1;
        const double cut = layout.full_paths ? 1e300 : layout.cut_ns;
        for (int depth = 1; depth <= max_depth; ++depth) {
            SurfaceHit hit;
            ++rays;
            if (!ctx.geometry.intersect(o, d, 1e-7f, 1e30f, hit)) return;
            t += hit.t * (inside ? inside_ior : 1.0f) / kSpeedOfLight;
            // Nothing this path reaches from here on can arrive inside this section.
            if (t >= cut) return;
            if (hit.light >= 0) return;  // lights absorb
            const MaterialDesc& m = sc.materials[hit.material];
            Vec3 nf = dot(d, hit.normal) < 0 ? hit.normal : -hit.normal;
            if (m.type == MaterialType::Diffuse) {
                if (depth >= 2 || e.direct_by_photons)
                    out.push_back({hit.position.x, hit.position.y, hit.position.z, nf.x, nf.y, nf.z,
                                   flux.x, flux.y, flux.z, static_cast<uint32_t>(depth), t});
                // Russian roulette from the third vertex on: survive with the albedo's maximum.
                float q = depth >= 3 ? std::min(1.0f, max_component(m.albedo)) : 1.0f;
                if (q <= 0 || (q < 1 && rng.uniform() >= q)) return;
                flux = flux * m.albedo * (1.0f / q);
                d = sample_cosine_hemisphere(nf, rng.uniform(), rng.uniform());
                o = hit.position + nf * ray_epsilon(hit.position, hit.t);
            } else {
                SpecularBounce b = specular_bounce(m, d, hit.normal, inside, rng);
                flux *= b.weight;
                if (b.inside_after != inside) inside_ior = m.ior;
                inside = b.inside_after;
                Vec3 side = dot(b.direction, hit.normal) > 0 ? hit.normal : -hit.normal;
                o = hit.position + side * ray_epsilon(hit.position, hit.t);
                d = b.direction;
            }
            if (is_black(flux)) return;
        }
    }
};

}  // namespace

uint64_t PhotonMap::bytes() const {
    uint64_t b = (cell_start_.capacity() + cursor_.capacity()) * sizeof(uint32_t) + slot_of_.capacity() * sizeof(uint32_t) +
                 (x_.capacity() + y_.capacity() + z_.capacity()) * sizeof(float) +
                 sorted_.capacity() * sizeof(PhotonRecord);
    for (const auto& v : batches_) b += v.capacity() * sizeof(PhotonRecord);
    return b;
}

void PhotonMap::build(const RenderContext& ctx, const SectionLayout& layout, int pass, int64_t count,
                      double cell_size, PhotonTraceCounters& counters) {
    const size_t nbatches = ctx.lights.has_emission() ? static_cast<size_t>((count + kBatch - 1) / kBatch) : 0;
    batches_.resize(nbatches);
    tbb::parallel_for(size_t(0), nbatches, [&](size_t b) {
        std::vector<PhotonRecord>& out = batches_[b];
        out.clear();
        Rng rng(ctx.scene.render.seed, 2, static_cast<uint64_t>(pass), b);
        PhotonPath path{ctx, layout, out};
        int64_t n = std::min<int64_t>(kBatch, count - static_cast<int64_t>(b) * kBatch);
        for (int64_t i = 0; i < n; ++i) path.trace(rng);
        counters.photons.fetch_add(static_cast<uint64_t>(n), std::memory_order_relaxed);
        counters.rays.fetch_add(path.rays, std::memory_order_relaxed);
    });

    // Counting sort by hash slot, in batch order: the layout is the same for any thread count.
    size_t total = 0;
    for (const auto& v : batches_) total += v.size();
    counters.stored.fetch_add(total, std::memory_order_relaxed);
    uint32_t table = 1024;
    while (table < 2 * total && table < (1u << 30)) table <<= 1;
    mask_ = table - 1;
    inv_cell_ = static_cast<float>(1.0 / std::max(cell_size, 1e-12));
    cell_start_.assign(static_cast<size_t>(table) + 1, 0);
    slot_of_.resize(total);
    size_t i = 0;
    for (const auto& v : batches_)
        for (const PhotonRecord& p : v) {
            uint32_t h = hash_cell(cell(p.x), cell(p.y), cell(p.z));
            slot_of_[i++] = h;
            ++cell_start_[h + 1];
        }
    for (size_t s = 1; s <= table; ++s) cell_start_[s] += cell_start_[s - 1];
    x_.resize(total); y_.resize(total); z_.resize(total);
    sorted_.resize(total);
    cursor_.assign(cell_start_.begin(), cell_start_.end() - 1);
    i = 0;
    for (const auto& v : batches_)
        for (const PhotonRecord& p : v) {
            uint32_t dst = cursor_[slot_of_[i++]]++;
            x_[dst] = p.x; y_[dst] = p.y; z_[dst] = p.z;
            sorted_[dst] = p;
        }
}

}  // namespace sl
