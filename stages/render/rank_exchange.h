#pragma once
// How one render is shared among processes (MPI ranks), without naming MPI: the render stages
// only see this narrow interface; the MPI implementation is a plugin loaded when a launcher
// started the process (pipeline/distributed/). A render with no exchange is one process.
//
// The division: every rank traces a contiguous share of each pass's photon batches, and the
// batches are all-gathered so that every rank holds the photon map one process would build
// (same records, same order); pixels are dealt to the ranks in tiles of 16, round-robin, and a
// rank keeps buckets, radii and photon counts for its own pixels only.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sl {

// The pixels one rank owns: tiles of kTile pixels (the section buffer's tiles), tile t going to
// rank t mod ranks. Local pixel i is global pixel global(i); a rank's local pixels are in
// global order, and its local tiles are whole tiles of the image.
struct PixelShare {
    static constexpr size_t kTile = 16;
    int rank = 0, ranks = 1;
    size_t total = 0;  // pixels in the whole image

    size_t tiles() const { return (total + kTile - 1) / kTile; }
    size_t local_tiles() const {
        const size_t t = tiles(), r = static_cast<size_t>(rank), n = static_cast<size_t>(ranks);
        return t > r ? (t - r + n - 1) / n : 0;
    }
    size_t count() const {  // pixels this rank owns
        const size_t lt = local_tiles();
        if (lt == 0) return 0;
        const size_t last_global_tile = (lt - 1) * static_cast<size_t>(ranks) + static_cast<size_t>(rank);
        return (lt - 1) * kTile + std::min(kTile, total - last_global_tile * kTile);
    }
    size_t global(size_t local) const {
        return ((local / kTile) * static_cast<size_t>(ranks) + static_cast<size_t>(rank)) * kTile + local % kTile;
    }
    // global()'s inverse: false when another rank owns the pixel.
    bool local_of(size_t global_pixel, size_t& local) const {
        const size_t tile = global_pixel / kTile, n = static_cast<size_t>(ranks);
        if (tile % n != static_cast<size_t>(rank)) return false;
        local = (tile / n) * kTile + global_pixel % kTile;
        return true;
    }
};

// Independent streams of collective calls, each made by one thread at a time in the same order
// on every rank: the passes of the section being rendered (radius, agreement to stop), the
// photons of the next pass (exchanged while this pass's camera pass runs), and the frames on
// their way to rank 0 (which may be another section's, while the next one renders).
enum class Channel { Passes = 0, Frames = 1, Photons = 2 };
inline constexpr int kChannels = 3;

// Memory that the ranks of one machine map together (RankExchange::one_node only): one block
// per rank, which its rank alone writes and every rank reads. On one machine this replaces
// sending the photon records from rank to rank. Kept by the exchange for the job.
class SharedBlocks {
public:
    virtual ~SharedBlocks() = default;
    // Collective (every rank, at the same point, on this block set's channel): afterwards this
    // rank's block holds at least `bytes`, and asked(r) is what rank r asked for. The blocks keep
    // their contents unless some rank's block had to grow.
    virtual void reserve(uint64_t bytes) = 0;
    virtual char* block(int rank) const = 0;  // 8-byte aligned at least (checked)
    virtual uint64_t asked(int rank) const = 0;
    virtual uint64_t capacity(int rank) const = 0;
    // Collective: every rank's writes to the blocks before it are seen by every rank after it.
    virtual void fence() = 0;
};

// The block sets a render shares: Traced, each rank's batch counts and volume photons; Grid, the
// photon grid (its records and cell starts, in rank 0's block: each rank places and sorts its
// part of it there) and, at the end of every rank's block, its batches' partition counts.
enum class Shared { Traced = 0, Grid = 1 };
inline constexpr int kSharedSets = 2;

class RankExchange {
public:
    virtual ~RankExchange() = default;
    virtual int rank() const = 0;
    virtual int ranks() const = 0;

    // Every rank's bytes, concatenated in rank order, received by rank 0 only (the others get
    // empty `all`); counts[r]: rank r's bytes.
    virtual void gather(Channel c, const void* mine, uint64_t bytes, std::vector<char>& all,
                        std::vector<uint64_t>& counts) = 0;
    virtual double max(Channel c, double v) = 0;
    virtual void max(Channel c, double* values, int n) = 0;  // element-wise, in place
    virtual int max(Channel c, int v) = 0;
    virtual void sum(Channel c, uint64_t* values, int n) = 0;
    // Every rank's part of one array, on every rank, in place: rank r holds elements
    // [bounds[r], bounds[r + 1]) of `data` (each `element_bytes` long) and receives the others.
    virtual void all_gather_in_place(Channel c, void* data, uint64_t element_bytes,
                                     const std::vector<uint64_t>& bounds) = 0;
    // Rank 0's value, on every rank.
    virtual bool broadcast(Channel c, bool v) = 0;
    virtual double broadcast(Channel c, double v) = 0;
    // Rank 0's bytes, on every rank (resized to them).
    virtual void broadcast(Channel c, std::vector<char>& bytes) = 0;
    // Rank 0's `all`, cut into counts[r] bytes for rank r (counts and `all` are read on rank 0
    // only): each rank's part in `mine`.
    virtual void scatter(Channel c, const std::vector<char>& all, const std::vector<uint64_t>& counts,
                         std::vector<char>& mine) = 0;
    // One of the job's shared block sets (one_node only), its collectives on channel `c`
    // (the same channel every time for a set).
    virtual SharedBlocks& shared(Shared which, Channel c) = 0;
    // Ends every rank of the job at once (after this rank printed why).
    [[noreturn]] virtual void abort(int code) = 0;

    // Whether every rank runs on one machine: there the ranks map the photon grid together
    // (shared), divide its sort among themselves and send no record; across a network they
    // all-gather the records and each sorts the grid whole.
    bool one_node = false;

    // Rank 0's receive buffer for gathered images, per channel, kept from frame to frame: a
    // fresh one is fresh pages to fault in (and zero) for every frame. Each channel is used by
    // one thread at a time, and the buffer lives as long as the job's exchange.
    std::vector<char> image_buffer[kChannels];

    // Payload bytes this rank sent and received (rank 0's own share excluded), per channel.
    uint64_t sent[kChannels] = {}, received[kChannels] = {};
    uint64_t collectives[kChannels] = {};
    // Seconds in the data step of (all-)gathers, after the sizes' exchange has lined the ranks
    // up: the transfer itself, without waiting for a slower rank.
    double transfer_seconds[kChannels] = {};
};

}  // namespace sl
