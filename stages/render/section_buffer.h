#pragma once
// The per-pixel state of one convergence: the progressive radius and photon count, and one
// RGB accumulator per time slot. Every pass adds its own estimate (direct light, emission and
// gathered photons already divided by pi R_i^2 and the pass's photon count) so the image is the
// running sum divided by the number of passes: no per-pass rescale of the buckets is needed.
#include <cstdint>
#include <vector>

#include "stages/render/section_layout.h"

namespace sl {

struct SectionBuffer {
    SectionBuffer(size_t pixels, const SectionLayout& layout, float initial_radius, bool ambient);

    // Bytes this buffer will hold, computed before anything is allocated.
    static uint64_t bytes_needed(size_t pixels, int slots, bool ambient);

    float* slot(size_t pixel, int s) { return &accum[(pixel * slots + s) * 3]; }
    const float* slot(size_t pixel, int s) const { return &accum[(pixel * slots + s) * 3]; }

    SectionLayout layout;
    int slots;
    std::vector<double> radius2;        // per pixel, m^2
    std::vector<double> photon_count;   // per pixel: N of progressive photon mapping
    std::vector<float> accum;           // pixel-major: [pixel][slot][rgb], sum over passes
    std::vector<float> ambient;         // [pixel][rgb] sum over passes; empty without ambient
    double max_radius = 0;              // the largest radius, for the photon grid's cell size
    int passes_done = 0;
};

}  // namespace sl
