// The frame stages: assembly (a frame's image from its section's buckets, or read back from
// --exr-dir for a resumed section) and the write stage (the only one that hands images to the
// outputs, in frame order).
#include <malloc.h>

#include "foundation/errors.h"
#include "pipeline/distributed/image_gather.h"
#include "pipeline/exposure.h"
#include "pipeline/exposure_preview.h"
#include "pipeline/pipeline_run.h"
#include "pipeline/resume.h"
#include "stages/output/exr_frame_check.h"
#include "stages/output/exr_io.h"

namespace sl {
namespace {

// What an EXR of this section says about itself: the passes it got, and whether an interrupt
// cut the section short (then --resume renders it further instead of keeping it).
FrameSink::Metadata frame_metadata(const Section& s) {
    FrameSink::Metadata m{{kPassesKey, std::to_string(s.passes)}};
    if (s.partial) m[kInterruptedKey] = "1";
    return m;
}

}  // namespace

FramePtr PipelineRun::assemble(const FrameJob& in) {
    const auto t0 = Clock::now();
    Section& s = *in.section;
    auto out = std::make_shared<FrameImage>();
    out->section = in.section;
    out->frame = in.frame;
    FrameImage& img = *out;
    if (s.from_disk) {
        // Checked again as it is read: the file may have changed since --resume judged it.
        // With ranks, only rank 0 (which judged it) reads it: the image is whole there.
        if (root_)
            img.rgb = read_verified_exr(job_.exr_files->exr_frame_path(in.frame),
                                        resume_expectation(ctx_.width, ctx_.height, job_.fingerprint, in.frame));
    } else {
        if (!s.assembler) {
            s.assembler.emplace(*s.run.buffer, mode_, ctx_.timeline.pulse_buckets);
            if (s.last) decide_from_steady(s, img);
        }
        img.rgb = frame_buffers_.take();
        s.assembler->frame(in.frame, img.rgb);
        whole_image(img.rgb);
        if (wants_cube_) {
            if (in.frame == 0) {
                s.assembler->before_plane(img.before);
                whole_image(img.before);
            }
            img.bucket = frame_buffers_.take();
            s.assembler->bucket_plane(in.frame, img.bucket);
            whole_image(img.bucket);
            if (s.last && in.frame + 1 == s.layout.end_frame) {
                s.assembler->after_plane(img.after);
                whole_image(img.after);
            }
        }
    }
    stats_.assembly += since(t0);
    if (job_.frame_assembled) job_.frame_assembled(in.frame);
    return out;
}

// The last section's steady image rides with its first frame, and with it, when no exposure was
// fixed yet (one section holds every frame), the exposure it gives and whether the scene is black.
// Decided here, handed to the outputs only by the write stage; nothing else sets the exposure
// meanwhile: with several sections the preview fixed it before.
void PipelineRun::decide_from_steady(Section& s, FrameImage& img) {
    std::vector<float> steady;
    s.assembler->steady(steady);
    whole_image(steady);
    // (a camera ray per pixel: only when the exposure or the black check needs it)
    const std::vector<uint8_t> lamps =
        exposure_pending_ || job_.check_black ? emitter_pixels(ctx_) : std::vector<uint8_t>();
    if (exposure_pending_) {
        ExposureMeter meter(mode_, job_.exposure_rule, lamps);
        measure_buffer(*s.run.buffer, ctx_, meter, &steady);
        if (root_) img.exposure = meter.decide();
        exposure_pending_ = false;
    }
    if (root_ && job_.check_black) {
        ExposureMeter light(EmissionMode::Constant, {}, lamps);
        light.add_steady(steady.data(), ctx_.pixels());
        stats_.steady_black = light.decide().black;
    }
    if (root_) img.steady = std::move(steady);
}

bool PipelineRun::write(FrameImage& img) {
    // The sequencer before this stage makes this impossible; were it ever broken, no stream
    // gets a frame out of order.
    if (img.frame != next_frame_)
        throw RuntimeFailure("internal error: frame " + std::to_string(img.frame) + " reached the writers before frame " +
                             std::to_string(next_frame_));
    ++next_frame_;
    const auto t0 = Clock::now();
    if (root_) {
        if (img.exposure) outputs_.set_exposure_plan(*img.exposure);
        if (!img.steady.empty()) outputs_.write_steady(img.steady, frame_metadata(*img.section));
        outputs_.take_frame(img.frame, img.rgb, img.section->from_disk, frame_metadata(*img.section));
    }
    if (!img.before.empty()) outputs_.write_cube_plane(img.before);
    if (!img.bucket.empty()) outputs_.write_cube_plane(img.bucket);
    if (!img.after.empty()) outputs_.write_cube_plane(img.after);
    stats_.writing += since(t0);
    frame_buffers_.give(std::move(img.rgb));
    frame_buffers_.give(std::move(img.bucket));
    const bool last = img.frame + 1 == img.section->layout.end_frame;
    if (last) free_section(*img.section);
    return last;
}

// A section's last frame is written: free its buckets before another section may allocate its own.
void PipelineRun::free_section(Section& s) {
    if (!s.partial) ++stats_.sections_done;
    // Its frames are in --exr-dir now: they, not the checkpoint, are what --resume reads.
    if (job_.checkpointer && !s.partial && job_.exr_files && !job_.exr_files->exr_dir().empty())
        job_.checkpointer->remove(s.layout.index);
    s.assembler.reset();
    s.run.buffer.reset();
    malloc_trim(0);  // hand the section's freed working memory back before the next one grows
    outputs_.section_written(s.layout.index);
}

}  // namespace sl
