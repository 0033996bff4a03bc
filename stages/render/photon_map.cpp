#include "stages/render/photon_map.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstring>

#include "core/glossy_path.h"
#include "core/photon_qmc.h"
#include "core/rng.h"
#include "core/specular_path.h"
#include "core/surface_material.h"

namespace sl {
namespace {

// Follows one photon path, storing a record at every diffuse vertex whose light is not
// already computed as direct light (vertex 1 is direct, except for lasers), and, in a medium,
// a volume photon at every scattering event but the first vertex's (single scattering, which
// the camera pass computes by next-event estimation; a laser's is kept: no camera ray meets
// its delta direction).
struct PhotonPath {
    const RenderContext& ctx;
    const SectionLayout& layout;
    std::vector<PhotonRecord>& out;
    const HomogeneousMedium* medium;   // null in vacuum
    std::vector<VolumePhoton>* volume;  // with a medium
    uint64_t rays = 0;
    // A carried section (SectionLayout::carried) has no use for light arriving before its first
    // bucket: such photons are traced on (they may scatter later light) but not stored. Only
    // without camera_tof, where a photon's time is its arrival time; with it, the camera leg
    // may still move an earlier photon into the section.
    const bool drop_early = layout.carried && !ctx.render.camera_tof;
    bool early(double t) const { return drop_early && ctx.timeline.bucket(t) < layout.first_bucket; }
    const bool single_by_photons = ctx.single_scatter_by_photons;
    const BucketFinder bucket{ctx.timeline};

    void store(Vec3 p, Vec3 flux, Vec3 ns, Vec3 d, int depth, double t) {
        const int64_t j = std::clamp<int64_t>(bucket(t), -(int64_t(1) << 30), int64_t(1) << 30);
        out.push_back({p.x, p.y, p.z, flux.x, flux.y, flux.z, encode_normal(ns), encode_normal(-d),
                       static_cast<uint32_t>(depth), static_cast<int32_t>(j), t});
    }

    void trace(Rng& rng) { trace_from(ctx.lights.emit(rng), rng); }

    void trace_from(const EmittedPhoton& e, Rng& rng) {
        const RenderDesc& settings = ctx.render;
        const int max_depth = settings.max_depth;
        Vec3 o = e.origin, d = e.direction, flux = e.flux;
        double t = e.start_ns;
        bool inside = false;
        float inside_ior = 1;
        const double cut = layout.full_paths ? 1e300 : layout.cut_ns;
        for (int depth = 1; depth <= max_depth; ++depth) {
            SurfaceHit hit;
            ++rays;
            const bool found = ctx.geometry.intersect(o, d, 1e-7f, 1e30f, hit);
            if (medium && !inside) {  // dielectric solids hold no medium
                float t0, t1;
                if (medium->clip(o, d, 0, found ? hit.t : 1e30f, t0, t1)) {
                    float u1 = rng.uniform(), u2 = rng.uniform();
                    FreeFlight ff = medium->sample_free_flight(t1 - t0, u1, u2);
                    flux *= ff.weight;  // at an event: Tr sigma_s / pdf; else Tr / P(no event)
                    if (ff.scattered) {
                        const float s = t0 + ff.distance;
                        t += s / kSpeedOfLight;
                        if (t >= cut || is_black(flux)) return;
                        o = o + d * s;
                        // Single scattering (depth 1: straight from the light) is the camera
                        // pass's next-event estimate, except for a laser's delta beam.
                        if (volume && !early(t) && (depth >= 2 || e.direct_by_photons || single_by_photons))
                            volume->push_back({o.x, o.y, o.z, d.x, d.y, d.z, flux.x, flux.y, flux.z,
                                               static_cast<uint32_t>(depth), t});
                        if (depth == max_depth) return;
                        // Russian roulette as at surfaces, on the event's weight.
                        float q = depth >= 3 ? std::min(1.0f, max_component(ff.weight)) : 1.0f;
                        if (q < 1 && rng.uniform() >= q) return;
                        if (q < 1) flux = flux * (1.0f / q);
                        d = medium->sample_phase(d, rng.uniform(), rng.uniform());
                        continue;
                    }
                    if (is_black(flux)) return;
                }
            }
            if (!found) return;
            t += hit.t * (inside ? inside_ior : 1.0f) / kSpeedOfLight;
            // Nothing this path reaches from here on can arrive inside this section.
            if (t >= cut) return;
            if (hit.light >= 0) return;  // lights absorb
            const SurfaceMaterial& m = ctx.materials[hit.material];
            const bool toward = dot(d, hit.normal) < 0;
            Vec3 nf = toward ? hit.normal : -hit.normal;
            if (m.type == MaterialType::Diffuse) {
                Vec3 ns = toward ? hit.shading_normal : -hit.shading_normal;
                if ((depth >= 2 || e.direct_by_photons) && !early(t))
                    store(hit.position, flux, ns, d, depth, t);
                const Vec3 albedo = albedo_at(m, hit);
                // Russian roulette from the third vertex on: survive with the albedo's maximum.
                float q = depth >= 3 ? std::min(1.0f, max_component(albedo)) : 1.0f;
                if (q <= 0 || (q < 1 && rng.uniform() >= q)) return;
                flux = flux * albedo * (1.0f / q);
                // Scatter about the shading normal; a direction below the true surface ends the path.
                const Vec3 nm = m.normal_texture ? shading_normal_facing(m, hit, d) : ns;
                d = sample_cosine_hemisphere(nm, rng.uniform(), rng.uniform());
                if (dot(d, nf) <= 0) return;
                o = hit.position + nf * ray_epsilon(hit.position, hit.t);
            } else if (m.glossy != GlossyUse::None) {
                // A GGX surface: a record where visible points may gather, then a sampled bounce
                // (importance transport), with Russian roulette as at specular vertices.
                const bsdf::Bsdf b = bsdf_at(m, hit);  // textures looked up once for both uses
                if (glossy_use_at(m, b) == GlossyUse::Gather && (depth >= 2 || e.direct_by_photons) && !early(t))
                    store(hit.position, flux, toward ? hit.shading_normal : -hit.shading_normal, d, depth, t);
                const Vec3 w = follow_glossy(m, b, hit, o, d, inside, inside_ior, rng, bsdf::Transport::Importance);
                flux *= w;
                const float q = depth >= 3 ? std::min(1.0f, max_component(w)) : 1.0f;
                if (q < 1 && q > 0) {
                    if (rng.uniform() >= q) return;
                    flux = flux * (1.0f / q);
                }
            } else {
                const Vec3 w = follow_specular(m, hit, o, d, inside, inside_ior, rng);
                flux *= w;
                // Russian roulette as at diffuse vertices, on the event's weight (a mirror's
                // reflectance; clear glass weighs 1 and is never cut).
                const float q = depth >= 3 ? std::min(1.0f, max_component(w)) : 1.0f;
                if (q < 1 && q > 0) {
                    if (rng.uniform() >= q) return;
                    flux = flux * (1.0f / q);
                }
            }
            if (is_black(flux)) return;
        }
    }
};

// Sizes a buffer the grid sort overwrites whole. When it must grow, the old block is freed
// first and nothing is copied (its records are last pass's), and 1/16 is kept spare: the
// record count moves a little from pass to pass, and std::vector's own growth copied the
// stale records into a block twice the size (three maps' worth alive for a moment).
template <class T>
void size_for_overwrite(std::vector<T>& v, size_t n) {
    if (n > v.capacity()) {
        std::vector<T>().swap(v);
        v.reserve(n + n / 16);
    }
    v.resize(n);
}

}  // namespace

uint64_t PhotonMap::bytes() const {
    uint64_t b = sorted_.capacity() * sizeof(PhotonRecord) +
                 (cell_start_.capacity() + partition_start_.capacity()) * sizeof(uint32_t) +
                 exchanged_.capacity();
    if (shared_)  // this rank's blocks of the memory shared with the others
        for (Shared set : {Shared::Traced, Shared::Grid})
            b += shared_->shared(set, set == Shared::Traced ? Channel::Photons : Channel::Passes).capacity(shared_->rank());
    for (const std::vector<PhotonRecord>& group : scratch_) b += group.capacity() * sizeof(PhotonRecord);
    for (const std::vector<uint32_t>& slots : scratch_slot_) b += slots.capacity() * sizeof(uint32_t);
    for (const Batch& v : batches_)
        b += v.records.capacity() * sizeof(PhotonRecord) + (v.partition_begin.capacity() + v.hash.capacity()) * 4 +
             v.volume.capacity() * sizeof(VolumePhoton);
    return b;
}

bool PhotonMap::build(const RenderContext& ctx, const SectionLayout& layout, int pass, int64_t count,
                      double cell_size, PhotonTraceCounters& counters, VolumePhotonMap* volume,
                      const std::atomic<bool>* abandon) {
    if (!trace(ctx, layout, pass, count, counters, volume != nullptr, abandon, cell_size)) return false;
    finish(ctx, cell_size, counters, volume);
    return true;
}

bool PhotonMap::trace(const RenderContext& ctx, const SectionLayout& layout, int pass, int64_t count,
                      PhotonTraceCounters& counters, bool with_volume, const std::atomic<bool>* abandon,
                      double cell_size) {
    traced_inv_cell_ = cell_size > 0 ? inverse_cell(cell_size) : 0;
    const HomogeneousMedium* medium = ctx.medium ? &*ctx.medium : nullptr;
    const bool volume = medium && with_volume;
    const size_t nbatches = ctx.lights.has_emission() ? static_cast<size_t>((count + kBatch - 1) / kBatch) : 0;
    batches_.resize(nbatches);
    RankExchange* ex = ctx.exchange;
    const size_t own_first = ex ? share_begin(nbatches, ex->rank(), ex->ranks()) : 0;
    const size_t own_end = ex ? share_begin(nbatches, ex->rank() + 1, ex->ranks()) : nbatches;
    traced_bounds_.assign(1, 0);
    for (int r = 0; ex && r < ex->ranks(); ++r) traced_bounds_.push_back(share_begin(nbatches, r + 1, ex->ranks()));
    const auto t0 = std::chrono::steady_clock::now();
    const PhotonQmc qmc(ctx.render.seed, static_cast<uint64_t>(pass));
    tbb::parallel_for(own_first, own_end, [&](size_t b) {
        Batch& batch = batches_[b];
        batch.records.clear();
        // A fresh batch starts with room for 4 records a path (a closed room stores about 2.5):
        // grown by doubling from nothing, the first pass's records were copied several times
        // and the threads took turns in the kernel for each block. Pages not written stay unmapped.
        if (batch.records.capacity() == 0) batch.records.reserve(size_t(kBatch) * 4);
        batch.received = nullptr;
        batch.elsewhere = false;
        batch.volume.clear();
        batch.hash.clear();
        if (abandon && abandon->load(std::memory_order_relaxed)) return;
        Rng rng(ctx.render.seed, 2, static_cast<uint64_t>(pass), b);
        PhotonPath path{ctx, layout, batch.records, medium, volume ? &batch.volume : nullptr};
        int64_t n = std::min<int64_t>(kBatch, count - static_cast<int64_t>(b) * kBatch);
        // The batch's points first (8 KiB a 256 photons, in this core's cache), then the paths.
        constexpr int kChunk = 256;
        float first[kChunk * PhotonQmc::kDims];
        PhotonQmc::Walk walk(qmc, static_cast<uint64_t>(b) * kBatch);
        for (int64_t i = 0; i < n; ++i) {
            const int in_chunk = static_cast<int>(i % kChunk);
            if (ctx.photon_qmc) {
                if (in_chunk == 0) walk.fill(first, static_cast<int>(std::min<int64_t>(kChunk, n - i)));
                rng.use_first(first + in_chunk * PhotonQmc::kDims, PhotonQmc::kDims);
            }
            path.trace(rng);
        }
        if (traced_inv_cell_ > 0) {  // the batch's records are still in this core's cache
            batch.hash.resize(batch.records.size());
            for (size_t i = 0; i < batch.records.size(); ++i) batch.hash[i] = hash_at(batch.records[i], traced_inv_cell_);
        }
        counters.photons.fetch_add(static_cast<uint64_t>(n), std::memory_order_relaxed);
        counters.rays.fetch_add(path.rays, std::memory_order_relaxed);
    });
    if (abandon && abandon->load()) return false;
    size_t own = 0, own_volume = 0;
    for (size_t b = own_first; b < own_end; ++b) {
        own += batches_[b].records.size();
        own_volume += batches_[b].volume.size();
    }
    counters.stored.fetch_add(own, std::memory_order_relaxed);  // this rank's own records
    if (volume) counters.stored_volume.fetch_add(own_volume, std::memory_order_relaxed);
    own_trace_.photons = std::clamp<int64_t>(count - static_cast<int64_t>(own_first) * kBatch, 0,
                                             static_cast<int64_t>(own_end - own_first) * kBatch);
    const auto t1 = std::chrono::steady_clock::now();
    own_trace_.trace_seconds = std::chrono::duration<double>(t1 - t0).count();
    if (ex) exchange_batches(*ex, nbatches);
    own_trace_.exchange_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    return true;
}

void PhotonMap::finish(const RenderContext& ctx, double cell_size, PhotonTraceCounters& counters,
                       VolumePhotonMap* volume) {
    if (!ctx.medium) volume = nullptr;
    inv_cell_ = inverse_cell(cell_size);
    size_t total = 0;
    for (const Batch& v : batches_) total += v.count();
    sort_into_grid(total, ctx.exchange);
    if (volume) {
        std::vector<const std::vector<VolumePhoton>*> parts;
        parts.reserve(batches_.size());
        for (const Batch& v : batches_) parts.push_back(&v.volume);
        volume->build(parts);
    }
}

// A rank's message: per own batch its record and volume-photon counts (two uint32), then the
// records, then the volume photons, batch after batch. Unpacked in batch order, every rank ends
// with the same batches, hence the same grid and the same BVH.
// Across machines, one all-gather per pass: the message sizes go first (one small reduction),
// so that each rank packs its batches straight into its place in the gathered buffer and the
// all-gather runs in place (no copy of a rank's own message; the buffer is kept between passes).
// On one machine the message holds no records (each rank puts its own into the shared grid,
// sort_into_grid): each rank writes the counts and volume photons into its own shared block and
// the others read them there after a barrier. The block is written again only for the pass
// after next, by which time every rank has sorted this pass (the grid's barriers come between).
void PhotonMap::exchange_batches(RankExchange& ex, size_t nbatches) {
    const int n = ex.ranks(), me = ex.rank();
    const size_t first = share_begin(nbatches, me, n), end = share_begin(nbatches, me + 1, n);
    const bool shared = ex.one_node && n > 1;
    static_assert(sizeof(PhotonRecord) % 8 == 0 && sizeof(VolumePhoton) % 8 == 0, "messages in 8-byte units");
    std::vector<uint64_t> counts(static_cast<size_t>(n), 0);  // bytes, multiples of 8
    uint64_t& bytes = counts[static_cast<size_t>(me)];
    bytes = (end - first) * 2 * sizeof(uint32_t);
    for (size_t b = first; b < end; ++b)
        bytes += (shared ? 0 : batches_[b].records.size() * sizeof(PhotonRecord)) +
                 batches_[b].volume.size() * sizeof(VolumePhoton);
    auto pack = [&](char* at) {
        auto put = [&](const void* src, size_t len) {
            if (len) std::memcpy(at, src, len);
            at += len;
        };
        for (size_t b = first; b < end; ++b) {
            const uint32_t c[2] = {static_cast<uint32_t>(batches_[b].records.size()),
                                   static_cast<uint32_t>(batches_[b].volume.size())};
            put(c, sizeof c);
        }
        if (!shared)
            for (size_t b = first; b < end; ++b) put(batches_[b].records.data(), batches_[b].records.size() * sizeof(PhotonRecord));
        for (size_t b = first; b < end; ++b) put(batches_[b].volume.data(), batches_[b].volume.size() * sizeof(VolumePhoton));
    };
    std::vector<const char*> message(static_cast<size_t>(n));  // where each rank's message is
    if (shared) {
        SharedBlocks& traced = ex.shared(Shared::Traced, Channel::Photons);
        traced.reserve(bytes);
        pack(traced.block(me));
        traced.fence();
        for (int r = 0; r < n; ++r) message[static_cast<size_t>(r)] = traced.block(r);
    } else {
        ex.sum(Channel::Photons, counts.data(), n);
        std::vector<uint64_t> bounds(static_cast<size_t>(n) + 1, 0);  // in 8-byte units
        for (size_t r = 0; r < counts.size(); ++r) bounds[r + 1] = bounds[r] + counts[r] / 8;
        size_for_overwrite(exchanged_, bounds.back() * 8);
        pack(exchanged_.data() + bounds[static_cast<size_t>(me)] * 8);
        ex.all_gather_in_place(Channel::Photons, exchanged_.data(), 8, bounds);
        for (int r = 0; r < n; ++r) message[static_cast<size_t>(r)] = exchanged_.data() + bounds[static_cast<size_t>(r)] * 8;
    }
    // Where each other rank's batch starts in the message (a cheap scan). Its records are then
    // sorted from there, in place; its volume photons are copied into the batch (in parallel:
    // every rank makes these copies, so they must not be one thread's work).
    struct Source {
        const PhotonRecord* records;
        const char* volume;
        uint32_t n_records, n_volume;
        bool other;
    };
    std::vector<Source> from(nbatches, Source{nullptr, nullptr, 0, 0, false});
    for (int r = 0; r < n; ++r) {
        const char* at = message[static_cast<size_t>(r)];
        const size_t f = share_begin(nbatches, r, n), e = share_begin(nbatches, r + 1, n);
        if (r != me) {
            const char* data = at + (e - f) * 2 * sizeof(uint32_t);
            for (size_t b = f; b < e; ++b) {
                uint32_t c[2];
                std::memcpy(c, at + (b - f) * sizeof c, sizeof c);
                from[b].other = true;
                from[b].records = shared ? nullptr : reinterpret_cast<const PhotonRecord*>(data);  // 8-byte aligned
                from[b].n_records = c[0];
                from[b].n_volume = c[1];
                if (!shared) data += c[0] * sizeof(PhotonRecord);
            }
            for (size_t b = f; b < e; ++b) {
                from[b].volume = data;
                data += from[b].n_volume * sizeof(VolumePhoton);
            }
        }
    }
    tbb::parallel_for(size_t(0), nbatches, [&](size_t b) {
        const Source& src = from[b];
        if (!src.other) return;  // this rank's own
        batches_[b].received = src.records;
        batches_[b].elsewhere = shared;
        batches_[b].received_count = src.n_records;
        batches_[b].volume.resize(src.n_volume);
        if (src.n_volume) std::memcpy(batches_[b].volume.data(), src.volume, src.n_volume * sizeof(VolumePhoton));
    });
}

// A stable two-step counting sort by hash slot that runs in parallel and gives the same order
// for any thread count: records are first grouped by the slot's top bits (each batch copies its
// records to its own ranges of the grid array, in batch order), then each group is
// counting-sorted on its own, from a copy in the thread's scratch buffer back into its range.
// Both steps read their source in order: a record copied straight from its batch to its final
// place would be a random read from a map far larger than the caches, and those reads were most
// of the sort's time. The second step works within one group (a 64th of the map), which fits in
// a core's cache. Each record is hashed once before the first step (by its tracing task when
// that knew the cell size) and the first step reads only those 4 bytes to place it; the second
// hashes the group's copy again, in cache, rather than stage a slot per record through memory.
//
// With ranks on one machine, the grid is one array in memory they share (in rank 0's block),
// and the ranks divide the sort as threads divide it in one process: each rank hashes only the
// batches it traced and publishes their partition counts (in its own block); a barrier; every
// rank computes the same offsets from all the counts, and each copies its own batches' records
// into their places in the shared grid; a barrier; each rank sorts a contiguous run of the
// partitions (about 1/N of the records: the runs are cut by record count); a barrier, and every
// rank gathers from the grid one process builds. No record is hashed, read or copied by more
// than one rank. Ranks on several machines each sort the whole map into their own grid, as one
// process does: sending the sorted parts would cost more than sorting them (docs/distributed.md).
void PhotonMap::sort_into_grid(size_t total, RankExchange* ex) {
    uint32_t table = 1u << 10;
    while (table < 2 * total && table < (1u << 30)) table <<= 1;
    mask_ = table - 1;
    const int shift = std::countr_zero(table) - kPartitionBits;
    const size_t parts = size_t(1) << kPartitionBits;
    const size_t nbatches = batches_.size();
    const int ranks = ex && ex->one_node ? ex->ranks() : 1;
    const int me = ranks > 1 ? ex->rank() : 0;
    // The batches this rank places: those it traced on one machine, else all of them.
    auto first_of = [&](int r) { return traced_bounds_[static_cast<size_t>(r)]; };
    const size_t batch_first = ranks > 1 ? first_of(me) : 0;
    const size_t batch_end = ranks > 1 ? first_of(me + 1) : nbatches;

    // Where the grid goes. Its last pass's readers are done: every rank has ended its camera
    // pass before any rank sorts the next (the pass's reduction lies between). On one machine
    // rank 0's block holds the grid and its cells, and every rank's block ends with the
    // partition counts of its batches.
    PhotonRecord* grid = nullptr;
    uint32_t* cells = nullptr;
    SharedBlocks* shared = ranks > 1 ? &ex->shared(Shared::Grid, Channel::Passes) : nullptr;
    const uint64_t counts_bytes = parts * sizeof(uint32_t);  // per batch
    auto counts_of = [&](size_t b, int owner) {  // batch b's partition counts, in its owner's block
        const uint64_t own_bytes = (first_of(owner + 1) - first_of(owner)) * counts_bytes;
        return reinterpret_cast<uint32_t*>(shared->block(owner) + shared->asked(owner) - own_bytes) +
               (b - first_of(owner)) * parts;
    };
    if (shared) {
        const uint64_t cells_at = (static_cast<uint64_t>(total) * sizeof(PhotonRecord) + 63) / 64 * 64;
        const uint64_t counts_at = me == 0 ? cells_at + (static_cast<uint64_t>(table) + 1) * sizeof(uint32_t) : 0;
        shared->reserve(counts_at + (batch_end - batch_first) * counts_bytes);
        grid = reinterpret_cast<PhotonRecord*>(shared->block(0));
        cells = reinterpret_cast<uint32_t*>(shared->block(0) + cells_at);
        shared_ = ex;
    } else {
        size_for_overwrite(sorted_, total);
        size_for_overwrite(cell_start_, static_cast<size_t>(table) + 1);
        grid = sorted_.data();
        cells = cell_start_.data();
    }

    // Each record's hash, once: made by the tracing task when it knew this cell size, else here.
    const bool traced_hashes = traced_inv_cell_ == inv_cell_;
    tbb::parallel_for(batch_first, batch_end, [&](size_t b) {
        Batch& batch = batches_[b];
        batch.partition_begin.assign(parts, 0);
        const PhotonRecord* records = batch.data();
        const size_t n = batch.count();
        if (!traced_hashes || batch.received || batch.hash.size() != n) {
            batch.hash.resize(n);
            for (size_t i = 0; i < n; ++i) batch.hash[i] = hash_at(records[i], inv_cell_);
        }
        for (size_t i = 0; i < n; ++i) ++batch.partition_begin[(batch.hash[i] & mask_) >> shift];
        if (shared) std::memcpy(counts_of(b, me), batch.partition_begin.data(), counts_bytes);
    });
    if (shared) {  // the other ranks' counts
        shared->fence();
        for (int r = 0; r < ranks; ++r) {
            if (r == me) continue;
            for (size_t b = first_of(r); b < first_of(r + 1); ++b) {
                const uint32_t* c = counts_of(b, r);
                batches_[b].partition_begin.assign(c, c + parts);
            }
        }
    }
    partition_start_.assign(parts + 1, 0);
    uint32_t offset = 0;
    for (size_t part = 0; part < parts; ++part) {
        partition_start_[part] = offset;
        for (Batch& batch : batches_) {
            uint32_t n = batch.partition_begin[part];
            batch.partition_begin[part] = offset;
            offset += n;
        }
    }
    partition_start_[parts] = offset;
    // This rank's partitions [own_first, own_end): all of them in one process, and with ranks
    // on several machines.
    std::vector<size_t> part_bound(static_cast<size_t>(ranks) + 1, parts);
    part_bound[0] = 0;
    for (int r = 1; r < ranks; ++r) {  // the first partition at or past the rank's share of the records
        size_t p = part_bound[static_cast<size_t>(r) - 1];
        while (p < parts && static_cast<uint64_t>(partition_start_[p]) * static_cast<uint64_t>(ranks) <
                                static_cast<uint64_t>(total) * static_cast<uint64_t>(r))
            ++p;
        part_bound[static_cast<size_t>(r)] = p;
    }
    const size_t own_first = part_bound[static_cast<size_t>(me)], own_end = part_bound[static_cast<size_t>(me) + 1];
    tbb::parallel_for(batch_first, batch_end, [&](size_t b) {
        Batch& batch = batches_[b];
        std::vector<uint32_t>& cursor = batch.partition_begin;  // write cursors
        const PhotonRecord* records = batch.data();
        const uint32_t* hash = batch.hash.data();
        const size_t n = batch.count();
        for (size_t i = 0; i < n; ++i) grid[cursor[(hash[i] & mask_) >> shift]++] = records[i];
    });
    if (shared) shared->fence();  // every batch's records in their partitions
    tbb::parallel_for(own_first, own_end, [&](size_t part) {
        const uint32_t first_slot = static_cast<uint32_t>(part) << shift, slots = 1u << shift;
        uint32_t* start = cells + first_slot;
        std::fill(start, start + slots, 0u);
        const uint32_t lo = partition_start_[part], hi = partition_start_[part + 1];
        // The group's records in staged order (batch after batch), and their slots, from this
        // copy (in the core's cache: cheaper than a second array of slots through memory).
        std::vector<PhotonRecord>& group = scratch_.local();
        group.assign(grid + lo, grid + hi);
        std::vector<uint32_t>& local = scratch_slot_.local();
        local.resize(hi - lo);
        for (uint32_t i = 0; i < hi - lo; ++i) ++start[local[i] = slot_of(group[i]) - first_slot];
        uint32_t run = lo;
        for (uint32_t s = 0; s < slots; ++s) {
            uint32_t n = start[s];
            start[s] = run;
            run += n;
        }
        // Back into the group's range with start[] as the cursor; afterwards start[s] is slot
        // s's end, so shift it back.
        for (uint32_t i = 0; i < hi - lo; ++i) grid[start[local[i]]++] = group[i];
        for (uint32_t s = slots - 1; s > 0; --s) start[s] = start[s - 1];
        start[0] = lo;
    });
    if (me == 0) cells[table] = static_cast<uint32_t>(total);
    if (shared) shared->fence();  // every rank's part is in place before any rank reads the grid
    grid_ = grid;
    cells_ = cells;
    grid_size_ = total;
}

void trace_photon_path(const RenderContext& ctx, const EmittedPhoton& e, Rng& rng, std::vector<PhotonRecord>& records,
                       std::vector<VolumePhoton>* volume) {
    const SectionLayout whole{};
    PhotonPath path{ctx, whole, records, ctx.medium ? &*ctx.medium : nullptr, ctx.medium ? volume : nullptr};
    path.trace_from(e, rng);
}

PilotYield pilot_yield(const RenderContext& ctx, int64_t paths) {
    PhotonMap map;
    PhotonTraceCounters counters;
    map.trace(ctx, SectionLayout{}, /*pass=*/0, paths, counters, ctx.medium.has_value());
    const double n = static_cast<double>(std::max<int64_t>(paths, 1));
    return {static_cast<double>(counters.stored.load()) / n, static_cast<double>(counters.stored_volume.load()) / n};
}

}  // namespace sl
