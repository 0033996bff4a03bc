#include "stages/render/section_layout.h"

#include <algorithm>
#include <stdexcept>

namespace sl {
namespace {

// Slots a section needs besides one per frame: the pulse's look-back buckets, "before", "after".
struct Extras {
    bool before, after;
    int look_back;
    int count() const { return look_back + before + after; }
};

Extras extras_of(const Timeline& tl, EmissionMode mode, int sections, int k) {
    const int pulse_buckets = tl.pulse_buckets;
    const bool last = k == sections - 1;
    // Arrival times are never negative: the first section has nothing earlier than its first
    // bucket unless the timeline starts after t = 0. Pulse frames need no earlier light; only
    // steady.exr (the last section) does.
    const bool earlier_light = k > 0 || tl.bucket(0.0) < -(pulse_buckets - 1);
    return {earlier_light && (mode == EmissionMode::Constant || last), last, pulse_buckets - 1};
}

// Frames per section: the lowest level L (frames + extras) with every section at least one
// frame, trimmed from the front down to exactly F frames.
std::vector<int> frames_per_section(const Timeline& tl, EmissionMode mode, int sections) {
    const int f = tl.frames;
    if (sections < 1 || sections > f) throw std::invalid_argument("sections must be in 1..frames");
    std::vector<int> extra(static_cast<size_t>(sections));
    for (int k = 0; k < sections; ++k) extra[k] = extras_of(tl, mode, sections, k).count();
    auto frames_at = [&](int64_t level) {
        int64_t n = 0;
        for (int e : extra) n += std::max<int64_t>(1, level - e);
        return n;
    };
    int64_t lo = 1, hi = static_cast<int64_t>(f) + *std::max_element(extra.begin(), extra.end());
    while (lo < hi) {  // the smallest level that holds every frame
        int64_t mid = (lo + hi) / 2;
        if (frames_at(mid) >= f) hi = mid;
        else lo = mid + 1;
    }
    std::vector<int> n(static_cast<size_t>(sections));
    int64_t excess = -f;
    for (int k = 0; k < sections; ++k) excess += n[k] = static_cast<int>(std::max<int64_t>(1, lo - extra[k]));
    for (int k = 0; k < sections && excess > 0; ++k)
        if (n[k] > 1 && n[k] + extra[k] == lo) --n[k], --excess;
    return n;
}

}  // namespace

std::vector<SectionLayout> make_sections(const Timeline& timeline, EmissionMode mode,
                                         int sections) {
    const std::vector<int> frames = frames_per_section(timeline, mode, sections);
    std::vector<SectionLayout> out;
    out.reserve(frames.size());
    int first = 0;
    for (int k = 0; k < sections; ++k) {
        SectionLayout s;
        s.index = k;
        s.first_frame = first;
        s.end_frame = first += frames[k];
        s.first_bucket = s.first_frame - (timeline.pulse_buckets - 1);
        s.full_paths = k == sections - 1;
        s.cut_ns = timeline.edge(s.end_frame);
        const Extras e = extras_of(timeline, mode, sections, k);
        s.has_before = e.before;
        s.has_after = e.after;
        out.push_back(s);
    }
    return out;
}

SectionLayout make_section(const Timeline& timeline, EmissionMode mode, int sections, int index) {
    return make_sections(timeline, mode, sections).at(static_cast<size_t>(index));
}

int max_section_slots(const Timeline& timeline, EmissionMode mode, int sections) {
    int most = 0;
    for (const SectionLayout& s : make_sections(timeline, mode, sections)) most = std::max(most, s.slots());
    return most;
}

}  // namespace sl
