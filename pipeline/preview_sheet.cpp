#include "pipeline/preview_sheet.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <vector>

#include "pipeline/distributed/image_gather.h"
#include "stages/output/png_io.h"
#include "stages/output/tone_map.h"
#include "stages/render/frame_assembly.h"

namespace sl {

PreviewSheet::PreviewSheet(std::string path, EmissionMode mode, int pulse_buckets, int width, int height,
                           RankExchange* ex)
    : path_(std::move(path)), ex_(ex), mode_(mode), pulse_buckets_(pulse_buckets), width_(width), height_(height) {}

void PreviewSheet::after_pass(const SectionBuffer& buffer, std::optional<double> exposure) {
    if (!enabled()) return;
    auto now = std::chrono::steady_clock::now();
    bool due = buffer.layout.index != last_section_ || std::chrono::duration<double>(now - last_).count() >= interval_;
    if (ex_) due = ex_->broadcast(Channel::Passes, due);  // rank 0's clock decides for every rank
    if (due) write(buffer, exposure);
}

void PreviewSheet::write(const SectionBuffer& buffer, std::optional<double> exposure) {
    if (!enabled() || buffer.passes_done == 0 || buffer.layout.frames() <= 0) return;
    auto t0 = std::chrono::steady_clock::now();
    const SectionLayout& l = buffer.layout;
    const int n = std::min(6, l.frames());
    const int cols = std::min(3, n), rows = (n + cols - 1) / cols;
    const int shrink = std::max(1, (width_ + 255) / 256);
    const int tw = std::max(1, width_ / shrink), th = std::max(1, height_ / shrink), gap = 2;
    const int sw = cols * tw + (cols - 1) * gap, sh = rows * th + (rows - 1) * gap;
    std::vector<float> sheet(static_cast<size_t>(sw) * sh * 3, 0.0f), rgb;
    FrameAssembler frames(buffer, mode_, pulse_buckets_);
    for (int k = 0; k < n; ++k) {
        const int f = l.first_frame + (n == 1 ? 0 : k * (l.frames() - 1) / (n - 1));
        frames.frame(f, rgb);
        if (ex_) gather_image(*ex_, static_cast<size_t>(width_) * height_, rgb, Channel::Passes);
        if (rgb.empty() || failed_) continue;  // not rank 0: its pixels are sent, nothing more
        const int x0 = (k % cols) * (tw + gap), y0 = (k / cols) * (th + gap);
        for (int y = 0; y < th; ++y)
            for (int x = 0; x < tw; ++x)
                for (int c = 0; c < 3; ++c) {
                    double sum = 0;
                    for (int dy = 0; dy < shrink; ++dy)
                        for (int dx = 0; dx < shrink; ++dx)
                            sum += rgb[(static_cast<size_t>(y * shrink + dy) * width_ + x * shrink + dx) * 3 + c];
                    sheet[(static_cast<size_t>(y0 + y) * sw + x0 + x) * 3 + c] =
                        static_cast<float>(sum / (shrink * shrink));
                }
    }
    if (failed_ || (ex_ && ex_->rank() != 0)) {
        last_section_ = l.index;
        return;
    }
    std::vector<uint8_t> srgb(sheet.size());
    tone_map_srgb8(sheet.data(), sw, sh, exposure.value_or(exposure_from_steady(sheet.data(), sw, sh)), srgb.data());
    try {
        write_png(path_, sw, sh, srgb.data());  // through a temporary sibling and a rename
    } catch (const std::exception& e) {  // a look at the render is not worth the render
        std::fprintf(stderr, "warning: --preview: %s\n", e.what());
        failed_ = true;
        return;
    }
    ++writes_;
    last_section_ = l.index;
    last_ = std::chrono::steady_clock::now();
    interval_ = std::max(3.0, 50 * std::chrono::duration<double>(last_ - t0).count());
}

}  // namespace sl
