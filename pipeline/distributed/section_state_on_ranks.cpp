#include "pipeline/distributed/section_state_on_ranks.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace sl {
namespace {

constexpr size_t kTile = PixelShare::kTile;

// The local pixels of `share` whose global index lies in [p0, p1) (p0 a whole tile): one run.
struct LocalRange {
    size_t begin = 0, end = 0;
};
LocalRange local_range(const PixelShare& share, size_t p0, size_t p1) {
    auto owned_before = [&](size_t tile) {  // this rank's tiles among global tiles [0, tile)
        const size_t r = static_cast<size_t>(share.rank), n = static_cast<size_t>(share.ranks);
        return tile > r ? (tile - r + n - 1) / n : 0;
    };
    const size_t t0 = p0 / kTile, t1 = (p1 + kTile - 1) / kTile;
    return {std::min(share.count(), owned_before(t0) * kTile), std::min(share.count(), owned_before(t1) * kTile)};
}

}  // namespace

uint64_t save_section_state_on_ranks(RankExchange& ex, const std::string& path, const SectionBuffer& buffer,
                                     const SectionStateId& id, bool finished) {
    const size_t pixels = buffer.share.total;
    const int slots = buffer.slots;
    std::vector<char> mine, all;
    std::vector<uint64_t> counts;
    // This rank's part of a chunk, to rank 0; there, every rank's part put in its place.
    auto exchange = [&](int array, size_t p0, size_t p1, char* out) {
        const size_t per = section_state_pixel_bytes(array, slots);
        const LocalRange l = local_range(buffer.share, p0, p1);
        mine.resize((l.end - l.begin) * per);
        if (!mine.empty()) copy_section_state_chunk(buffer, array, l.begin, l.end, mine.data());
        ex.gather(Channel::Passes, mine.data(), mine.size(), all, counts);
        if (!out) return;
        const char* at = all.data();
        for (int r = 0; r < ex.ranks(); ++r) {
            const PixelShare share{r, ex.ranks(), pixels};
            const LocalRange lr = local_range(share, p0, p1);
            if (counts[static_cast<size_t>(r)] != (lr.end - lr.begin) * per)
                throw std::logic_error("a rank sent a checkpoint part of the wrong size");
            for (size_t local = lr.begin; local < lr.end; local += kTile) {
                const size_t n = std::min(kTile, lr.end - local);
                std::memcpy(out + (share.global(local) - p0) * per, at, n * per);
                at += n * per;
            }
        }
    };
    SectionStateScalars v = section_state_scalars(buffer);
    v.pixels = pixels;
    if (ex.rank() != 0) {
        for_each_section_state_chunk(pixels, v.ambient,
                                     [&](int array, size_t p0, size_t p1) { exchange(array, p0, p1, nullptr); });
        return 0;
    }
    return save_section_state_from(path, id, v, finished, exchange);
}

std::unique_ptr<SectionBuffer> load_section_state_on_ranks(RankExchange& ex, const std::string& path,
                                                           const SectionStateId& expected, const SectionLayout& layout,
                                                           bool ambient, size_t pixels) {
    const PixelShare own{ex.rank(), ex.ranks(), pixels};
    auto b = std::make_unique<SectionBuffer>(own, layout, 0.0f, ambient);
    const int slots = layout.slots();
    std::vector<char> parts, mine;
    std::vector<uint64_t> counts;
    // Rank 0 cuts a chunk into the ranks' parts; each rank keeps its own.
    auto exchange = [&](int array, size_t p0, size_t p1, const char* chunk) {
        const size_t per = section_state_pixel_bytes(array, slots);
        if (chunk) {
            parts.clear();
            counts.assign(static_cast<size_t>(ex.ranks()), 0);
            for (int r = 0; r < ex.ranks(); ++r) {
                const PixelShare share{r, ex.ranks(), pixels};
                const LocalRange lr = local_range(share, p0, p1);
                for (size_t local = lr.begin; local < lr.end; local += kTile) {
                    const size_t n = std::min(kTile, lr.end - local);
                    const char* from = chunk + (share.global(local) - p0) * per;
                    parts.insert(parts.end(), from, from + n * per);
                }
                counts[static_cast<size_t>(r)] = (lr.end - lr.begin) * per;
            }
        }
        ex.scatter(Channel::Passes, parts, counts, mine);
        const LocalRange l = local_range(own, p0, p1);
        if (mine.size() != (l.end - l.begin) * per) throw std::logic_error("a checkpoint part of the wrong size");
        if (!mine.empty()) take_section_state_chunk(*b, array, l.begin, l.end, mine.data());
    };
    SectionStateScalars v;
    if (ex.rank() == 0) {
        load_section_state_into(path, expected, layout, ambient, exchange, &v);
    } else {
        for_each_section_state_chunk(pixels, ambient,
                                     [&](int array, size_t p0, size_t p1) { exchange(array, p0, p1, nullptr); });
    }
    // The file passed its checksum on rank 0 (else rank 0 threw, and its error ends the job).
    b->passes_done = static_cast<int>(ex.broadcast(Channel::Passes, static_cast<double>(v.passes_done)));
    b->max_radius = ex.broadcast(Channel::Passes, v.max_radius);
    b->volume_radius2 = ex.broadcast(Channel::Passes, v.volume_radius2);
    return b;
}

}  // namespace sl
