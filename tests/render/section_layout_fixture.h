#pragma once
// A one-section layout over `frames` frames with "before" and "after" slots: the shape the
// buffer and checkpoint tests fill and read back.
#include "stages/render/section_layout.h"

namespace sl::test {

inline SectionLayout whole_layout(int frames) {
    SectionLayout l;
    l.first_frame = 0, l.end_frame = frames, l.first_bucket = 0;
    l.has_before = true, l.has_after = true;
    return l;
}

}  // namespace sl::test
