#pragma once
// Where a render's frames go, in order: the program's outputs (FrameOutputs: EXR, PNG, video,
// cube) or, for the tests, the benchmarks and the report, images kept in memory
// (FramesInMemory). The pipeline calls the write methods from its write stage only, one frame
// at a time, so a sink needs no locking of its own.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/exposure.h"

namespace sl {

struct SectionBuffer;

class FrameSink {
public:
    using Metadata = std::map<std::string, std::string>;  // more EXR header entries for a frame
    virtual ~FrameSink() = default;

    // The exposure, decided once before frames flow, for a sink that tone-maps.
    virtual bool needs_exposure() const { return false; }
    virtual void set_exposure_plan(const ExposurePlan&) {}
    virtual std::optional<double> exposure() const { return std::nullopt; }
    // The transient cube's planes (write_cube_plane) are assembled only when asked for.
    virtual bool wants_cube() const { return false; }

    // Frames arrive in index order; the steady image comes just before the last section's
    // first frame. `on_disk`: the frame's EXR is already there (a resumed section).
    virtual void write_frame(int index, const std::vector<float>& rgb, bool on_disk = false,
                             const Metadata& extra = {}) = 0;
    // What the write stage calls: write_frame, unless the sink keeps the pixels (the Python
    // module): it may then swap `rgb` with a buffer of its own, of any size (the pipeline reuses
    // whatever it gets back), instead of copying a frame of megabytes.
    virtual void take_frame(int index, std::vector<float>& rgb, bool on_disk, const Metadata& extra) {
        write_frame(index, rgb, on_disk, extra);
    }
    virtual void write_steady(const std::vector<float>& rgb, const Metadata& extra = {}) = 0;
    virtual void write_cube_plane(const std::vector<float>&) {}

    // A section's raw state after its passes, before its frames are assembled (called by the
    // render stage: with two sections alive it may run while the previous one is written).
    virtual void section_rendered(int /*section*/, const SectionBuffer&) {}
    // A section's last frame was written (the write stage).
    virtual void section_written(int /*section*/) {}
};

}  // namespace sl
