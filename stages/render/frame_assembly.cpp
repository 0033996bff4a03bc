#include "stages/render/frame_assembly.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>

namespace sl {
namespace {

constexpr size_t kTile = SectionBuffer::kTile;

// Calls f(first pixel, pixels in tile) for every tile, tiles in parallel. A frame reads a few
// slots of every tile: 192 bytes each, tens of KiB apart with many frames, too far apart for the
// hardware to see the pattern, so every read waited on memory. The slots [first, last] of the
// tile kAhead further on are prefetched (when there are only a few; longer runs are contiguous).
template <class F>
void for_each_tile(const SectionBuffer& buffer, size_t pixels, int first, int last, F&& f) {
    constexpr size_t kAhead = 4;
    constexpr int kFewSlots = 4;
    const size_t tiles = (pixels + kTile - 1) / kTile;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles, 16), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t t = r.begin(); t != r.end(); ++t) {
            if (t + kAhead < r.end() && last - first < kFewSlots)
                for (int s = first; s <= last; ++s) {
                    const char* at = reinterpret_cast<const char*>(buffer.slot((t + kAhead) * kTile, s));
                    for (size_t b = 0; b < kTile * 3 * sizeof(float); b += 64) __builtin_prefetch(at + b, 0);
                }
            f(t * kTile, std::min(kTile, pixels - t * kTile));
        }
    });
}

float scale_of(const SectionBuffer& buffer) {
    return buffer.passes_done > 0 ? 1.0f / static_cast<float>(buffer.passes_done) : 0.0f;
}

// Where a pixel's running sum starts: a carried section's "before" slot is an average, so it
// enters the sum of passes as that average times the passes (exact in double: a float times an
// int), so that its frames cost what any other section's do.
double carried_start(const SectionBuffer& buffer, float carried) {
    return static_cast<double>(carried) * static_cast<double>(buffer.passes_done);
}

// Sums, in double and in slot order, a carried section's starting value and slots first..last,
// times `scale` (the steps of FrameAssembler::frame, so the results equal its frames).
void sum_carried(const SectionBuffer& buffer, size_t pixels, int first, int last, std::vector<float>& rgb) {
    const float scale = scale_of(buffer);
    rgb.assign(pixels * 3, 0.0f);
    for_each_tile(buffer, pixels, first, last, [&](size_t p0, size_t n) {
        double sum[kTile * 3];
        const float* c = buffer.slot(p0, 0);
        for (size_t i = 0; i < n * 3; ++i) sum[i] = carried_start(buffer, c[i]);
        for (int s = first; s <= last; ++s) {
            const float* src = buffer.slot(p0, s);
            for (size_t i = 0; i < n * 3; ++i) sum[i] += src[i];
        }
        for (size_t i = 0; i < n * 3; ++i) rgb[p0 * 3 + i] = static_cast<float>(sum[i]) * scale;
    });
}

}  // namespace

void carried_frame(const SectionBuffer& buffer, std::vector<float>& rgb) {
    const SectionLayout& l = buffer.layout;
    const int last = l.slot_of_bucket(l.end_frame - 1);
    if (l.carried) return sum_carried(buffer, buffer.radius2.size(), l.first_bucket_slot(), last, rgb);
    FrameAssembler(buffer, EmissionMode::Pulse, 1).slots(0, last, rgb);  // (no running sum needed)
}

void set_carried(SectionBuffer& buffer, const std::vector<float>& rgb) {
    if (!buffer.layout.carried) throw std::logic_error("this section carries nothing over");
    if (rgb.size() != buffer.radius2.size() * 3) throw std::logic_error("carried frame of the wrong size");
    for (size_t p = 0; p < buffer.radius2.size(); ++p) {
        float* c = buffer.slot(p, 0);
        c[0] = rgb[p * 3];
        c[1] = rgb[p * 3 + 1];
        c[2] = rgb[p * 3 + 2];
    }
}

FrameAssembler::FrameAssembler(const SectionBuffer& buffer, EmissionMode mode, int pulse_buckets)
    : buffer_(buffer), mode_(mode), pulse_buckets_(pulse_buckets),
      pixels_(buffer.radius2.size()),
      scale_(scale_of(buffer)),
      next_slot_(buffer.layout.first_bucket_slot()) {
    if (mode_ == EmissionMode::Constant) {
        running_.assign(pixels_ * 3, 0.0);
        const bool carried = buffer.layout.carried;
        if (buffer.layout.has_before)
            for_each_tile(buffer_, pixels_, 0, 0, [&](size_t p0, size_t n) {
                const float* src = buffer_.slot(p0, 0);
                for (size_t i = 0; i < n * 3; ++i)
                    running_[p0 * 3 + i] = carried ? carried_start(buffer_, src[i]) : src[i];
            });
    }
}

void FrameAssembler::add_ambient(std::vector<float>& rgb) const {
    if (buffer_.ambient.empty()) return;
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] += buffer_.ambient[i] * scale_;
}

void FrameAssembler::frame(int global_frame, std::vector<float>& rgb) {
    const SectionLayout& l = buffer_.layout;
    if (global_frame < l.first_frame || global_frame >= l.end_frame)
        throw std::logic_error("frame outside its section");
    rgb.resize(pixels_ * 3);
    const int last_slot = l.slot_of_bucket(global_frame);
    if (mode_ == EmissionMode::Constant) {
        if (last_slot < next_slot_) throw std::logic_error("constant frames must be assembled in order");
        const int from = next_slot_;
        for_each_tile(buffer_, pixels_, from, last_slot, [&](size_t p0, size_t n) {
            double* run = &running_[p0 * 3];
            for (int s = from; s <= last_slot; ++s) {
                const float* src = buffer_.slot(p0, s);  // the tile's pixels for slot s, in a row
                for (size_t i = 0; i < n * 3; ++i) run[i] += src[i];
            }
            for (size_t i = 0; i < n * 3; ++i) rgb[p0 * 3 + i] = static_cast<float>(run[i]) * scale_;
        });
        next_slot_ = last_slot + 1;
    } else {
        sum_slots(std::max(l.first_bucket_slot(), last_slot - pulse_buckets_ + 1), last_slot, rgb);
    }
    add_ambient(rgb);
}

void FrameAssembler::steady(std::vector<float>& rgb) const {
    if (buffer_.layout.carried) sum_carried(buffer_, pixels_, buffer_.layout.first_bucket_slot(), buffer_.slots - 1, rgb);
    else sum_slots(0, buffer_.slots - 1, rgb);
    add_ambient(rgb);
}

void FrameAssembler::slots(int first, int last, std::vector<float>& rgb) const { sum_slots(first, last, rgb); }

void FrameAssembler::sum_slots(int first, int last, std::vector<float>& rgb) const {
    rgb.assign(pixels_ * 3, 0.0f);
    for_each_tile(buffer_, pixels_, first, last, [&](size_t p0, size_t n) {
        double sum[kTile * 3] = {};
        for (int s = first; s <= last; ++s) {
            const float* src = buffer_.slot(p0, s);
            for (size_t i = 0; i < n * 3; ++i) sum[i] += src[i];
        }
        for (size_t i = 0; i < n * 3; ++i) rgb[p0 * 3 + i] = static_cast<float>(sum[i]) * scale_;
    });
}

void FrameAssembler::bucket_plane(int global_frame, std::vector<float>& rgb) const {
    int s = buffer_.layout.slot_of_bucket(global_frame);
    sum_slots(s, s, rgb);
}

void FrameAssembler::before_plane(std::vector<float>& rgb) const {
    if (buffer_.layout.carried) {  // the carried frame itself (no look-back buckets with constant light)
        rgb.assign(pixels_ * 3, 0.0f);
        for_each_tile(buffer_, pixels_, 0, 0, [&](size_t p0, size_t n) {
            const float* c = buffer_.slot(p0, 0);
            for (size_t i = 0; i < n * 3; ++i) rgb[p0 * 3 + i] = c[i];
        });
        return;
    }
    sum_slots(0, buffer_.layout.slot_of_bucket(buffer_.layout.first_frame) - 1, rgb);
}

void FrameAssembler::after_plane(std::vector<float>& rgb) const {
    int s = buffer_.layout.after_slot();
    if (s < 0) throw std::logic_error("this section keeps no after slot");
    sum_slots(s, s, rgb);
}

}  // namespace sl
