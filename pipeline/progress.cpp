#include "pipeline/progress.h"

#include <unistd.h>

#include <cstdio>
#include <string>

namespace sl {

ProgressBar::ProgressBar(bool enabled, int sections, int passes)
    : enabled_(enabled && isatty(STDERR_FILENO)), sections_(sections), passes_(passes),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

void ProgressBar::update(int section, int pass) {
    if (!enabled_) return;
    auto now = std::chrono::steady_clock::now();
    int total = sections_ * passes_, done = section * passes_ + pass;
    if (done < total && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    double elapsed = std::chrono::duration<double>(now - start_).count();
    double left = done > 0 ? elapsed * (total - done) / done : 0;
    const int width = 30;
    int filled = total > 0 ? width * done / total : width;
    std::string bar(static_cast<size_t>(filled), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r[%s] section %d/%d, pass %d/%d, %d:%02d left   ", bar.c_str(), section + 1,
                 sections_, pass, passes_, static_cast<int>(left) / 60, static_cast<int>(left) % 60);
    std::fflush(stderr);
    drawn_ = true;
}

void ProgressBar::finish() {
    if (drawn_) std::fprintf(stderr, "\n");
    drawn_ = false;
}

}  // namespace sl
