#pragma once
// Where the exposure comes from when no section of the render itself can provide it before
// frames flow: a short preview convergence, or (a finished render resumed) the EXR frames it
// wrote. Also the metering of a buffer that holds every frame, which the one-section render
// uses on itself.
#include <functional>
#include <vector>

#include "pipeline/exposure.h"
#include "pipeline/frame_outputs.h"
#include "stages/render/render_context.h"
#include "stages/render/section_renderer.h"

namespace sl {

// Feeds the meter every image it needs from a buffer that holds every frame (one section, or
// the preview): the steady image (given, or assembled here), and the frames themselves for
// pulses and --exposure-follow. With ranks every rank takes part (rank 0's meter decides).
void measure_buffer(const SectionBuffer& buffer, const RenderContext& ctx, ExposureMeter& meter,
                    const std::vector<float>* steady = nullptr);

struct ExposurePreview {
    ExposurePlan exposure;
    int passes = 0;       // passes the preview traced
    RenderCounts counts;  // its photons and rays
    double full_pass_seconds = 0;  // a full-resolution, full-path pass, as the preview's times predict it
};

// `stop(passes done)` ends it early (an interrupt, or --time-limit's share spent).
ExposurePreview exposure_from_preview(const RenderContext& ctx, const ExposureRule& rule,
                                      const std::function<bool(int)>& stop);

// A resumed render of one section: the same images, read back from its EXR files.
ExposurePlan exposure_from_disk(const RenderContext& ctx, const ExposureRule& rule, const FrameOutputs& outputs);

}  // namespace sl
