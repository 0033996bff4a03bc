#pragma once
// One pass's photons: traced in fixed batches (each with its own random stream and its own
// output slice, so no atomics and no dependence on the thread count), then counting-sorted into
// a hash grid whose cells are as wide as the largest gather radius.
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "core/oct_normal.h"
#include "core/rng.h"
#include "stages/render/render_context.h"
#include "stages/render/section_layout.h"
#include "stages/render/volume_photon_map.h"

namespace sl {

// 48 bytes: a pass holds every record twice (as traced, and sorted into the grid), and that
// memory does not shrink with the number of sections. The incoming direction is what a GGX
// visible point weighs the photon by (f(wo, wi)); Lambertian points do not read it.
struct PhotonRecord {
    float x, y, z;
    float r, g, b;      // flux of the emitted path (W), before dividing by the photon count
    OctNormal normal;   // surface normal facing the side the photon arrived from
    OctNormal incoming;  // unit direction back towards where the photon came from
    uint32_t depth;     // scattering vertices from the light, this one included
    // The timeline's bucket of t_ns, clamped to +-2^30 (which keeps every slot the same), in
    // what the double's alignment would pad: a gather without camera_tof takes each photon's
    // bucket from here instead of finding it for every photon it takes (a pulse's gather spent
    // a fifth of its time finding buckets).
    int32_t bucket = 0;
    double t_ns;        // arrival time at this point
};
static_assert(sizeof(PhotonRecord) == 48);

struct PhotonTraceCounters {
    std::atomic<uint64_t> photons{0}, rays{0}, stored{0}, stored_volume{0};
};

class PhotonMap {
public:
    // Traces `count` photon paths of pass `pass` and builds the grid with the given cell size.
    // With a medium in ctx, paths also scatter in it; its events go to `volume` when given.
    // `abandon`, when set during the pass (an interrupt), stops it within a batch of photons; the
    // map is then incomplete and must not be gathered from (build returns false).
    bool build(const RenderContext& ctx, const SectionLayout& layout, int pass, int64_t count,
               double cell_size, PhotonTraceCounters& counters, VolumePhotonMap* volume = nullptr,
               const std::atomic<bool>* abandon = nullptr);
    // build() in two steps: trace (this rank's batches, then, with ranks, the exchange) needs
    // no radius and touches only the batches, so it may run while a camera pass reads the grid
    // of the previous pass; finish sorts the batches into the grid (and the volume BVH). trace
    // returns false when abandoned (nothing was exchanged then). When the grid's cell size is
    // already known, passing it lets each tracing task hash its own records while they are
    // still in its cache (finish then need not read them for that); finish must get the same size.
    bool trace(const RenderContext& ctx, const SectionLayout& layout, int pass, int64_t count,
               PhotonTraceCounters& counters, bool with_volume, const std::atomic<bool>* abandon = nullptr,
               double cell_size = 0);
    void finish(const RenderContext& ctx, double cell_size, PhotonTraceCounters& counters, VolumePhotonMap* volume);

    size_t size() const { return grid_size_; }
    // This pass's surface records (grid order), e.g. for flux bookkeeping in tests.
    std::span<const PhotonRecord> records() const { return {grid_, grid_size_}; }
    uint64_t bytes() const;
    // Resident bytes of one pass's map of `records` surface records, computed before anything is
    // allocated (pipeline/memory_plan.cpp): each record in its batch and again in the grid, its
    // hash, and the cell table (a power of two of at least twice the records, plus one entry).
    static uint64_t bytes_needed(uint64_t records) {
        uint64_t table = 1u << 10;
        while (table < 2 * records && table < (1u << 30)) table <<= 1;
        return records * (2 * sizeof(PhotonRecord) + sizeof(decltype(Batch::hash)::value_type)) +
               (table + 1) * sizeof(decltype(cell_start_)::value_type);
    }

    // Calls f(const PhotonRecord&) for every photon within sqrt(r2) of p.
    template <class F>
    void for_each_near(float px, float py, float pz, float r2, F&& f) const;

    // With ranks: the batches each rank traces, as boundaries (stages/render/batch_shares.h);
    // equal counts unless set. Set between passes only, never while a trace runs.
    void set_batch_shares(std::vector<size_t> bounds) { shares_ = std::move(bounds); }
    // This rank's part of the last trace: wall time of its own batches and of the exchange
    // (waiting for the other ranks included), and its photon paths; what balances the shares.
    struct OwnTrace {
        double trace_seconds = 0, exchange_seconds = 0;
        int64_t photons = 0;
    };
    const OwnTrace& own_trace() const { return own_trace_; }

    // Photon paths per task (and per random stream). Small enough that the last tasks of a pass
    // leave the other threads little idle time (4096 left up to a twelfth of a 100k-photon pass
    // on one thread of two), large enough that a task's fixed costs do not show.
    static constexpr int kBatch = 1024;
    static constexpr int kPartitionBits = 6;  // the sort's first, parallel, radix step
    // The batches rank `rank` of `ranks` traces: a contiguous share, [first, end).
    static size_t first_batch(size_t nbatches, int rank, int ranks) {
        return nbatches * static_cast<size_t>(rank) / static_cast<size_t>(ranks);
    }

private:
    uint32_t hash_cell(int32_t ix, int32_t iy, int32_t iz) const {
        return static_cast<uint32_t>(ix) * 73856093u ^ static_cast<uint32_t>(iy) * 19349663u ^
               static_cast<uint32_t>(iz) * 83492791u;
    }
    int32_t cell(float v) const { return static_cast<int32_t>(std::floor(v * inv_cell_)); }
    static float inverse_cell(double cell_size) { return static_cast<float>(1.0 / std::max(cell_size, 1e-12)); }
    // A record's cell hash before the table mask: slot_of is this & mask_.
    uint32_t hash_at(const PhotonRecord& p, float inv_cell) const {
        auto c = [inv_cell](float v) { return static_cast<int32_t>(std::floor(v * inv_cell)); };
        return hash_cell(c(p.x), c(p.y), c(p.z));
    }
    void sort_into_grid(size_t total, RankExchange* ex);  // ex: with ranks, each sorts a share
    // The first batch of rank `rank`'s share (set_batch_shares, else first_batch).
    size_t share_begin(size_t nbatches, int rank, int ranks) const {
        return shares_.size() == static_cast<size_t>(ranks) + 1 && shares_.back() == nbatches
                   ? shares_[static_cast<size_t>(rank)]
                   : first_batch(nbatches, rank, ranks);
    }
    // With several ranks: each traced batches [first, end) of its own; afterwards every rank
    // holds every batch, as one process would have traced them.
    void exchange_batches(RankExchange& ex, size_t nbatches);

    struct Batch {
        std::vector<PhotonRecord> records;  // traced by this process
        // Or, with ranks across machines, another rank's records, read in place in the exchange
        // buffer (every rank sorts every record: a copy less is work that does not shrink with N).
        const PhotonRecord* received = nullptr;
        // Or, with ranks on one machine, another rank's batch, of which this rank knows only the
        // counts: its tracer puts its records into the shared grid.
        bool elsewhere = false;
        uint32_t received_count = 0;
        const PhotonRecord* data() const { return received ? received : records.data(); }
        size_t count() const { return received || elsewhere ? received_count : records.size(); }
        std::vector<uint32_t> partition_begin;  // where this batch's records of each partition go
        std::vector<uint32_t> hash;  // per record: hash_at(record, inv_cell_), for the grid sort
        std::vector<VolumePhoton> volume;  // medium scattering events (with a medium only)
    };
    uint32_t slot_of(const PhotonRecord& p) const { return hash_at(p, inv_cell_) & mask_; }

    std::vector<Batch> batches_;         // kept between passes: no reallocation per photon
    // Per thread, one partition's records while they are sorted back into place, and their
    // slots (kept: no reallocation per pass; about a 64th of a pass's records each).
    tbb::enumerable_thread_specific<std::vector<PhotonRecord>> scratch_;
    tbb::enumerable_thread_specific<std::vector<uint32_t>> scratch_slot_;
    float traced_inv_cell_ = 0;  // the cell size trace() hashed this rank's batches for (0: none)
    // The grid: records grouped by hash slot, and each slot's first record (table + 1 entries).
    // In this process's own arrays, or, with ranks on one machine, in memory they share.
    std::vector<PhotonRecord> sorted_;
    std::vector<uint32_t> cell_start_;
    const PhotonRecord* grid_ = nullptr;
    const uint32_t* cells_ = nullptr;
    size_t grid_size_ = 0;
    RankExchange* shared_ = nullptr;  // the exchange whose shared blocks hold the grid, if any
    std::vector<uint32_t> partition_start_;
    std::vector<char> exchanged_;  // every rank's batches, this rank's packed in place (kept: no reallocation per pass)
    std::vector<size_t> shares_;   // with ranks: each rank's first batch, and the batch count
    // The shares the last trace() used (the next pass's may already be set when its grid is sorted).
    std::vector<size_t> traced_bounds_;
    OwnTrace own_trace_;
    uint32_t mask_ = 0;
    float inv_cell_ = 1;
};

template <class F>
void PhotonMap::for_each_near(float px, float py, float pz, float r2, F&& f) const {
    if (grid_size_ == 0) return;
    float r = std::sqrt(r2);
    int32_t x0 = cell(px - r), x1 = cell(px + r);
    int32_t y0 = cell(py - r), y1 = cell(py + r);
    int32_t z0 = cell(pz - r), z1 = cell(pz + r);
    // Cells are twice the largest radius wide, so a gather sphere spans at most 2 cells per
    // axis (3 if rounding puts it on an edge): 27 is always enough, and every cell is visited.
    // The slots are found (and their starts prefetched) before any is read: each is a cache
    // miss in a table of megabytes, and this way they overlap instead of following each other.
    uint32_t seen[27];
    int nseen = 0;
    for (int32_t ix = x0; ix <= x1; ++ix)
        for (int32_t iy = y0; iy <= y1; ++iy)
            for (int32_t iz = z0; iz <= z1; ++iz) {
                uint32_t h = hash_cell(ix, iy, iz) & mask_;
                bool dup = false;  // two cells may share a slot: visit each slot once
                for (int k = 0; k < nseen; ++k) dup |= seen[k] == h;
                if (dup) continue;
                if (nseen == 27) continue;  // unreachable while r <= cell size; guards the array
                __builtin_prefetch(&cells_[h]);
                seen[nseen++] = h;
            }
    for (int k = 0; k < nseen; ++k)
        for (uint32_t i = cells_[seen[k]], e = cells_[seen[k] + 1]; i < e; ++i) {
            const PhotonRecord& ph = grid_[i];
            float dx = ph.x - px, dy = ph.y - py, dz = ph.z - pz;
            if (dx * dx + dy * dy + dz * dz < r2) f(ph);
        }
}

// Stored surface records and volume photons per photon path, from a pilot of `paths` full paths
// of the context's lights (pass 0, every path to its end, volume photons when there is a
// medium): the memory plan's photon terms and the beam estimate's automatic radius
// (render_context.cpp) are both made from it.
struct PilotYield {
    double records_per_path = 0, volume_per_path = 0;
};
PilotYield pilot_yield(const RenderContext& ctx, int64_t paths);

// One photon path from a given start, its records and (with a medium) volume photons appended
// as a pass stores them: for pilots that choose where the photons start (emission_aim_pilot.h).
void trace_photon_path(const RenderContext& ctx, const EmittedPhoton& e, Rng& rng, std::vector<PhotonRecord>& records,
                       std::vector<VolumePhoton>* volume);

}  // namespace sl
