#pragma once
// A frame sink that keeps the frames and the steady image in memory: what the tests, the
// benchmarks and the report render into (the program itself writes to FrameOutputs).
#include <functional>
#include <vector>

#include "pipeline/frame_sink.h"

namespace sl {

class FramesInMemory : public FrameSink {
public:
    std::vector<std::vector<float>> frames;  // by frame index, row 0 at the top
    std::vector<float> steady;
    bool keep_frames = true;  // false: frames are assembled (and timed) but not kept
    // Optional looks at a section's raw state after its passes and at the end of each section.
    std::function<void(int section, const SectionBuffer&)> on_section_rendered;
    std::function<void(int section)> on_section_written;

    void write_frame(int index, const std::vector<float>& rgb, bool, const Metadata&) override {
        if (!keep_frames) return;
        if (frames.size() <= static_cast<size_t>(index)) frames.resize(static_cast<size_t>(index) + 1);
        frames[static_cast<size_t>(index)] = rgb;
    }
    void write_steady(const std::vector<float>& rgb, const Metadata&) override { steady = rgb; }
    void section_rendered(int section, const SectionBuffer& buffer) override {
        if (on_section_rendered) on_section_rendered(section, buffer);
    }
    void section_written(int section) override {
        if (on_section_written) on_section_written(section);
    }
};

}  // namespace sl
