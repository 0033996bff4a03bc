#include "stages/render/frame_assembly.h"

#include <tbb/parallel_for.h>

#include <stdexcept>

namespace sl {

FrameAssembler::FrameAssembler(const SectionBuffer& buffer, EmissionMode mode, int pulse_buckets)
    : buffer_(buffer), mode_(mode), pulse_buckets_(pulse_buckets),
      pixels_(buffer.radius2.size()),
      scale_(buffer.passes_done > 0 ? 1.0f / static_cast<float>(buffer.passes_done) : 0.0f) {
    if (mode_ == EmissionMode::Constant) {
        running_.assign(pixels_ * 3, 0.0);
        for (size_t p = 0; p < pixels_; ++p)
            for (int c = 0; c < 3; ++c) running_[p * 3 + c] = buffer_.slot(p, 0)[c];
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
    int last_slot = l.slot_of_bucket(global_frame);
    if (mode_ == EmissionMode::Constant) {
        if (last_slot < next_slot_) throw std::logic_error("constant frames must be assembled in order");
        int from = next_slot_;
        tbb::parallel_for(size_t(0), pixels_, [&](size_t p) {
            for (int s = from; s <= last_slot; ++s)
                for (int c = 0; c < 3; ++c) running_[p * 3 + c] += buffer_.slot(p, s)[c];
            for (int c = 0; c < 3; ++c) rgb[p * 3 + c] = static_cast<float>(running_[p * 3 + c]) * scale_;
        });
        next_slot_ = last_slot + 1;
    } else {
        int first_slot = last_slot - pulse_buckets_ + 1;
        tbb::parallel_for(size_t(0), pixels_, [&](size_t p) {
            for (int c = 0; c < 3; ++c) {
                double sum = 0;
                for (int s = first_slot; s <= last_slot; ++s) sum += buffer_.slot(p, s)[c];
                rgb[p * 3 + c] = static_cast<float>(sum) * scale_;
            }
        });
    }
    add_ambient(rgb);
}

void FrameAssembler::steady(std::vector<float>& rgb) const {
    rgb.assign(pixels_ * 3, 0.0f);
    tbb::parallel_for(size_t(0), pixels_, [&](size_t p) {
        for (int c = 0; c < 3; ++c) {
            double sum = 0;
            for (int s = 0; s < buffer_.slots; ++s) sum += buffer_.slot(p, s)[c];
            rgb[p * 3 + c] = static_cast<float>(sum) * scale_;
        }
    });
    add_ambient(rgb);
}

}  // namespace sl
