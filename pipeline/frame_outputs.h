#pragma once
// Where finished frames go: linear EXR files, tone-mapped PNGs, the video encoder and the
// transient cube. All of them are opened (and checked) before rendering starts. Not thread
// safe: in the pipeline only the write stage calls it (its tone-mapping scratch buffer rgb8_
// is shared by frames and the steady image). The video encoder runs one frame behind, on
// another thread, while the next frame is assembled, tone-mapped and converted.
#include <cstdint>
#include <exception>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/run_options.h"
#include "foundation/timeline.h"
#include "pipeline/background_worker.h"
#include "pipeline/exposure.h"
#include "pipeline/frame_sink.h"
#include "stages/output/exr_header_scan.h"
#include "stages/output/hdf5_cube.h"
#include "stages/output/npy_cube.h"
#include "stages/output/sensor_images.h"
#include "stages/output/time_label.h"
#include "stages/output/video_encoder.h"

namespace sl {

struct OutputSettings {
    std::string video;  // "" for none, "-" for stdout
    std::string exr_dir, png_dir;
    std::string cube;   // "" for none
    CubeLayout cube_layout = CubeLayout::Slowlight;
    std::string hdf5;   // "" for none
    SensorRequest sensors;  // images written to exr_dir once every bin went past
    std::map<std::string, uint64_t> integers;  // the HDF5 file's whole-number attributes (seed, passes, ...)
    int width = 0, height = 0;
    double fps = 24;
    Timeline timeline;  // the frames and their edges (EXR headers, time labels, the cube's side-car)
    std::optional<double> exposure;              // fixed by the user
    ToneCurve tone = ToneCurve::Linear;
    bool label_time = false;                     // --label time on video and PNG frames
    std::map<std::string, std::string> metadata;  // stored in every EXR header
    std::vector<std::pair<int64_t, int64_t>> emitter_runs;  // the cube's side-car: pixels that see a lamp
};

class FrameOutputs : public FrameSink {
public:
    explicit FrameOutputs(const OutputSettings& settings);  // opens the encoder, makes dirs

    bool needs_exposure() const override { return !exposure_ && (encoder_ || !settings_.png_dir.empty()); }
    void set_exposure(double e) { exposure_ = e; }
    void set_exposure_plan(const ExposurePlan& plan) override {
        exposure_ = plan.base;
        per_frame_exposure_ = plan.per_frame;
    }
    std::optional<double> exposure() const override { return exposure_; }
    double frame_exposure(int index) const;
    // The cube's planes feed the cube, the HDF5 file and the sensor images.
    bool wants_cube() const override { return cube_ || cube_time_inner_ || hdf5_ || sensors_; }

    // `on_disk`: the EXR is already there (a resumed section), so only the rest is written.
    // `extra`: more EXR header entries for this frame (e.g. the passes it got).
    void write_frame(int index, const std::vector<float>& rgb, bool on_disk = false, const Metadata& extra = {}) override;
    void write_steady(const std::vector<float>& rgb, const Metadata& extra = {}) override;
    void write_cube_plane(const std::vector<float>& rgb) override;
    // Closes the video so that it plays, and the cube. A video that cannot be written (a pipe
    // whose reader is gone, a full disk) is dropped and the other outputs go on: its failure is
    // thrown here, once they are complete, or at once from write_frame when the video is the
    // only output (the encoder is a frame behind, so it surfaces a frame late).
    void finish();

    std::string exr_frame_path(int index) const;
    std::string exr_steady_path() const;
    const std::string& exr_dir() const { return settings_.exr_dir; }
    ExrSize frame_size() const { return {settings_.width, settings_.height}; }  // what reading back expects

    // "wrote out.mp4 (48 frames), exr/ (48 EXR frames + steady.exr)": what finish() left behind.
    std::string summary() const;

    double seconds_exr = 0, seconds_png = 0, seconds_video = 0;
    int64_t frames_written = 0;

private:
    void drop_video(std::exception_ptr failure);  // rethrows when nothing else is written

    OutputSettings settings_;
    std::optional<double> exposure_;
    std::vector<double> per_frame_exposure_;  // --exposure-follow
    std::unique_ptr<TimeLabel> label_;
    std::unique_ptr<VideoEncoder> encoder_;
    std::exception_ptr video_failure_;  // the dropped video's, thrown by finish()
    std::unique_ptr<NpyCubeWriter> cube_;
    std::unique_ptr<NpyTimeInnerWriter> cube_time_inner_;  // --cube-layout mitransient
    std::unique_ptr<Hdf5CubeWriter> hdf5_;
    std::unique_ptr<SensorImages> sensors_;
    int planes_seen_ = 0;  // the cube's planes so far: 0 before start_ns, k + 1 frame k, frames + 1 after
    bool all_planes() const { return planes_seen_ == settings_.timeline.frames + 2; }
    void write_sensor_images();
    std::vector<uint8_t> rgb8_;
    // The encoder, on a thread of its own: with one thread for the whole chain it set the pace
    // of a run's tail (x264 took 5 of its 7 ms a 512x512 frame). Last: it stops (ending its
    // frame) before what it reads goes. Only with a video.
    int staging_slot_ = 0;  // the encoder's staging frame the next frame is converted into
    std::optional<BackgroundWorker> encoding_;
};

}  // namespace sl
