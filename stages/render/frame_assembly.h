#pragma once
// Turns a finished section's time slots into frames (linear radiance, RGB, row 0 at the top).
// Constant emission: everything that arrived before the frame's end. Pulse of m buckets: the
// m buckets that end at the frame's end. Steady: every slot (only the full-path section).
#include <vector>

#include "config/scene_desc.h"
#include "stages/render/section_buffer.h"

namespace sl {

// A carried section (SectionLayout::carried) keeps the previous section's last frame in its
// "before" slot as an average, not a sum over passes; its frames start from it.
//
// The section's last frame without the ambient term: what the next section carries over. Equal,
// bit for bit, to that frame as FrameAssembler::frame() makes it (without ambient).
void carried_frame(const SectionBuffer& buffer, std::vector<float>& rgb);
// Puts `rgb` (this buffer's pixels, 3 floats each) into a carried section's "before" slot.
void set_carried(SectionBuffer& buffer, const std::vector<float>& rgb);

class FrameAssembler {
public:
    FrameAssembler(const SectionBuffer& buffer, EmissionMode mode, int pulse_buckets);

    // Frames must be asked for in increasing order (constant frames keep a running sum).
    void frame(int global_frame, std::vector<float>& rgb);
    void steady(std::vector<float>& rgb) const;

    // Planes of the transient cube (no ambient term): one frame's own bucket, everything that
    // arrived before the section's first frame, and everything at or after its end.
    void bucket_plane(int global_frame, std::vector<float>& rgb) const;
    void before_plane(std::vector<float>& rgb) const;
    void after_plane(std::vector<float>& rgb) const;
    // Slots first..last summed, over the passes (no ambient term).
    void slots(int first, int last, std::vector<float>& rgb) const;

private:
    void add_ambient(std::vector<float>& rgb) const;
    void sum_slots(int first, int last, std::vector<float>& rgb) const;  // slots first..last

    const SectionBuffer& buffer_;
    EmissionMode mode_;
    int pulse_buckets_;
    size_t pixels_;
    float scale_;                 // 1 / passes
    std::vector<double> running_;  // constant emission: sum of slots up to the last frame
    int next_slot_;
};

}  // namespace sl
