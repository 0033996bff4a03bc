#pragma once
// Which time buckets one section keeps. A section renders frames [first_frame, end_frame); its
// accumulator has one slot per bucket it needs, plus a "before" slot (everything earlier) where
// its frames or steady.exr need one, plus an "after" slot (everything later) in the section
// that accumulates steady.exr. Nothing else is kept: a slot is a float RGB image.
#include <cstdint>
#include <vector>

#include "config/scene_desc.h"
#include "foundation/timeline.h"

namespace sl {

struct SectionLayout {
    int index = 0;            // section number, 0-based
    int first_frame = 0, end_frame = 0;
    int64_t first_bucket = 0;  // first_frame - (pulse buckets - 1): pulse frames look back
    bool full_paths = true;    // false: photons are cut once they cannot reach end_frame
    double cut_ns = 0;         // with !full_paths: arrival times >= cut_ns are of no use
    bool has_before = true;    // a slot for arrivals before first_bucket
    bool has_after = true;     // a slot for arrivals at or after end_frame
    // Constant emission, sections after the first: the "before" slot holds the previous
    // section's last frame (its average over passes, ambient term excluded), carried over
    // instead of gathered again, and nothing is deposited there. Light arriving before the
    // section's first bucket is then of no use to it: a photon, shadow ray or deposit for it
    // is skipped (slot_of_bucket says -1).
    bool carried = false;

    int frames() const { return end_frame - first_frame; }
    int buckets() const { return static_cast<int>(end_frame - first_bucket); }
    int first_bucket_slot() const { return has_before ? 1 : 0; }
    int slots() const { return buckets() + has_before + has_after; }
    int before_slot() const { return has_before ? 0 : -1; }
    int after_slot() const { return has_after ? first_bucket_slot() + buckets() : -1; }
    // Slot of a bucket index; -1 where the section keeps nothing (arrivals it has no use for).
    int slot_of_bucket(int64_t j) const {
        if (j < first_bucket) return carried ? -1 : before_slot();
        if (j >= end_frame) return after_slot();
        return static_cast<int>(j - first_bucket) + first_bucket_slot();
    }
};

// K consecutive sections. Only the last one traces full paths and keeps an "after" slot,
// because it alone also accumulates steady.exr; constant emission needs a "before" slot in
// every section that can receive earlier light. Frames are shared out so that the sections'
// slot counts, and so their buffers, are as equal as possible.
std::vector<SectionLayout> make_sections(const Timeline& timeline, EmissionMode mode,
                                         int sections);
SectionLayout make_section(const Timeline& timeline, EmissionMode mode, int sections, int index);

// The largest slot count among make_sections(...): what one section's buffer must hold.
int max_section_slots(const Timeline& timeline, EmissionMode mode, int sections);

}  // namespace sl
