#include "stages/render/section_layout.h"

namespace sl {

SectionLayout make_section(const Timeline& timeline, int pulse_buckets, int sections, int index) {
    SectionLayout s;
    s.index = index;
    int64_t f = timeline.frames;
    s.first_frame = static_cast<int>(f * index / sections);
    s.end_frame = static_cast<int>(f * (index + 1) / sections);
    s.first_bucket = s.first_frame - (pulse_buckets - 1);
    s.full_paths = index == sections - 1;
    s.cut_ns = timeline.edge(s.end_frame);
    return s;
}

}  // namespace sl
