#pragma once
// --preview FILE.png: while a section renders, a contact sheet of a few of its frames (up to 6,
// spread over the section, each shrunk to at most 256 pixels wide) assembled from the passes
// done so far, rewritten atomically every few seconds so a user can watch it converge. Making
// the sheet reads the whole section buffer, so the interval grows to keep that under 2% of the
// render.
#include <chrono>
#include <optional>
#include <string>

#include "config/scene_desc.h"
#include "stages/render/section_buffer.h"

namespace sl {

class PreviewSheet {
public:
    // With several ranks (`ex`) every rank makes the same calls: the frames' pixels come
    // together on rank 0, which alone writes the sheet and whose clock says when it is due.
    PreviewSheet(std::string path, EmissionMode mode, int pulse_buckets, int width, int height,
                 RankExchange* ex = nullptr);
    bool enabled() const { return !path_.empty(); }

    // After a pass: writes the sheet if it is due (first pass of a section, then every interval).
    void after_pass(const SectionBuffer& buffer, std::optional<double> exposure);
    void write(const SectionBuffer& buffer, std::optional<double> exposure);
    int writes() const { return writes_; }

private:
    std::string path_;
    RankExchange* ex_ = nullptr;
    bool failed_ = false;  // rank 0 could not write it: no more tries (the ranks still take part)
    EmissionMode mode_;
    int pulse_buckets_, width_, height_;
    std::chrono::steady_clock::time_point last_{};
    int last_section_ = -1;
    double interval_ = 3;  // seconds
    int writes_ = 0;
};

}  // namespace sl
