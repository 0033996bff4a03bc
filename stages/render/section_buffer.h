#pragma once
// The per-pixel state of one convergence: the progressive radius and photon count, and one
// RGB accumulator per time slot. Every pass adds its own estimate (direct light, emission and
// gathered photons already divided by pi R_i^2 and the pass's photon count) so the image is the
// running sum divided by the number of passes: no per-pass rescale of the buckets is needed.
#include <cstdint>
#include <vector>

#include "stages/render/zeroed_page_allocator.h"
#include "stages/render/rank_exchange.h"
#include "stages/render/section_layout.h"

namespace sl {

struct SectionBuffer {
    SectionBuffer(size_t pixels, const SectionLayout& layout, float initial_radius, bool ambient);
    // Only the pixels `share` gives this rank (several ranks render one image).
    SectionBuffer(const PixelShare& share, const SectionLayout& layout, float initial_radius, bool ambient);

    // Each pixel's own initial radius, from radii of the whole image (row-major); before the
    // first pass only.
    void set_initial_radii(const std::vector<float>& image_radii);

    // Bytes this buffer will hold, computed before anything is allocated.
    static uint64_t bytes_needed(size_t pixels, int slots, bool ambient);

    // Pixels are kept in tiles of kTile: a tile stores slot 0 of its pixels, then slot 1, ...
    // A frame then reads kTile pixels' values in one run, and the gather, which walks pixels
    // in order, finds a tile's slots together in cache.
    static constexpr size_t kTile = 16;
    size_t offset(size_t pixel, int s) const {
        return ((pixel / kTile * slots + static_cast<size_t>(s)) * kTile + pixel % kTile) * 3;
    }
    float* slot(size_t pixel, int s) { return &accum[offset(pixel, s)]; }
    const float* slot(size_t pixel, int s) const { return &accum[offset(pixel, s)]; }
    static size_t padded(size_t pixels) { return (pixels + kTile - 1) / kTile * kTile; }

    SectionLayout layout;
    PixelShare share;  // which pixels of the image these are (all of them in one process)
    int slots;
    // Indexed by the pixel's place among this buffer's pixels (share.global() maps it back).
    std::vector<double> radius2;        // per pixel, m^2
    std::vector<double> photon_count;   // per pixel: N of progressive photon mapping
    std::vector<float, ZeroedPageAllocator<float>> accum;  // [tile][slot][pixel in tile][rgb], sum over passes
    std::vector<float> ambient;         // [pixel][rgb] sum over passes; empty without ambient
    double max_radius = 0;              // the largest radius, for the photon grid's cell size
    double volume_radius2 = 0;          // the beam estimate's radius^2 this pass (with a medium)
    int passes_done = 0;
};

}  // namespace sl
