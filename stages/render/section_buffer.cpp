#include "stages/render/section_buffer.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>

namespace sl {

SectionBuffer::SectionBuffer(size_t pixels, const SectionLayout& l, float initial_radius, bool with_ambient)
    : layout(l), share{0, 1, pixels}, slots(l.slots()) {
    double r2 = static_cast<double>(initial_radius) * initial_radius;
    radius2.assign(pixels, r2);
    photon_count.assign(pixels, 0.0);
    // The allocator's memory is zero already (resize does not fill it again). Its pages are
    // touched here, by every thread: on a virtual machine a fresh page can cost far more than
    // zeroing it, and one thread faulting in a 150 MB buffer left the other core idle.
    accum.resize(padded(pixels) * static_cast<size_t>(slots) * 3);
    constexpr size_t kPage = 4096 / sizeof(float), kChunk = 512 * kPage;  // 4 KiB pages, 2 MiB chunks
    float* data = accum.data();
    const size_t n = accum.size();
    tbb::parallel_for(size_t(0), (n + kChunk - 1) / kChunk, [&](size_t c) {
        for (size_t i = c * kChunk, e = std::min(n, i + kChunk); i < e; i += kPage) data[i] = 0.0f;
    });
    if (with_ambient) ambient.assign(pixels * 3, 0.0f);
    max_radius = initial_radius;
}

SectionBuffer::SectionBuffer(const PixelShare& s, const SectionLayout& l, float initial_radius, bool with_ambient)
    : SectionBuffer(s.count(), l, initial_radius, with_ambient) {
    share = s;
}

void SectionBuffer::set_initial_radii(const std::vector<float>& image_radii) {
    if (image_radii.size() != share.total) throw std::logic_error("SectionBuffer: radii of another image");
    for (size_t i = 0; i < radius2.size(); ++i) {
        const double r = image_radii[share.global(i)];
        radius2[i] = r * r;
    }
    // The whole image's largest, not this rank's: every rank's photon grid is the same.
    max_radius = *std::max_element(image_radii.begin(), image_radii.end());
}

uint64_t SectionBuffer::bytes_needed(size_t pixels, int slots, bool with_ambient) {
    uint64_t per_pixel = 2 * sizeof(double);
    if (with_ambient) per_pixel += 3 * sizeof(float);
    return per_pixel * pixels + static_cast<uint64_t>(padded(pixels)) * slots * 3 * sizeof(float);
}

}  // namespace sl
