#pragma once
// Which time buckets one section keeps. A section renders frames [first_frame, end_frame); its
// accumulator has one slot per bucket it needs plus a "before" slot (everything earlier, for
// constant emission) and an "after" slot (everything later, for steady.exr).
#include <cstdint>

#include "core/timeline.h"

namespace sl {

struct SectionLayout {
    int index = 0;            // section number, 0-based
    int first_frame = 0, end_frame = 0;
    int64_t first_bucket = 0;  // first_frame - (pulse buckets - 1): pulse frames look back
    bool full_paths = true;    // false: photons are cut once they cannot reach end_frame
    double cut_ns = 0;         // with !full_paths: arrival times >= cut_ns are of no use

    int frames() const { return end_frame - first_frame; }
    int buckets() const { return static_cast<int>(end_frame - first_bucket); }
    int slots() const { return buckets() + 2; }
    int after_slot() const { return buckets() + 1; }
    // Slot of a bucket index: 0 before the section's buckets, after_slot() past them.
    int slot_of_bucket(int64_t j) const {
        if (j < first_bucket) return 0;
        if (j >= end_frame) return after_slot();
        return static_cast<int>(j - first_bucket) + 1;
    }
};

// K consecutive sections of nearly equal size; only the last one traces full paths, because
// it alone also accumulates steady.exr.
SectionLayout make_section(const Timeline& timeline, int pulse_buckets, int sections, int index);

}  // namespace sl
