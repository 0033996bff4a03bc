#include "pipeline/frame_outputs.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <utility>

#include <nlohmann/json.hpp>
#include <tbb/task_group.h>

#include "foundation/constants.h"
#include "foundation/errors.h"
#include "stages/output/atomic_file.h"
#include "stages/output/exr_frame_check.h"
#include "stages/output/exr_io.h"
#include "stages/output/png_io.h"
#include "stages/output/tone_map.h"

namespace sl {
namespace {

// A number as text that reads back to the same double.
std::string exact(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

const char* tone_name(ToneCurve t) {
    return t == ToneCurve::Filmic ? "filmic" : t == ToneCurve::Log ? "log" : "linear";
}

void make_output_dir(const std::string& dir, const char* flag) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir))
        throw RuntimeFailure(std::string(flag) + " " + dir + ": cannot create the directory" +
                             (ec ? ": " + ec.message() : std::string()));
}

std::string numbered(const std::string& dir, const char* ext, int index) {
    char name[64];
    std::snprintf(name, sizeof name, "frame_%04d.%s", index, ext);
    return (std::filesystem::path(dir) / name).string();
}

template <class F>
double timed(F&& f) {
    auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The cube's side-car: what its planes mean, so that `retime` and users need nothing else.
void write_cube_sidecar(const OutputSettings& s) {
    nlohmann::json j;
    j["format"] = "slowlight transient cube 1";
    if (s.cube_layout == CubeLayout::Mitransient) {
        // mitransient's transient array: only the frames' bins, time in optical path length.
        j["cube_layout"] = "mitransient";
        j["layout"] = "float32 radiance (W sr^-1 m^-2), shape (height, width, frames, 3): [y, x, k] is what arrived "
                      "in frame k, whose optical path lengths are [start_opl + k bin_width_opl, start_opl + (k + 1) "
                      "bin_width_opl) metres; what arrived before start_ns or after end_ns is not included, nor the "
                      "ambient term";
    } else {
        j["cube_layout"] = "slowlight";
        j["layout"] = "float32 radiance (W sr^-1 m^-2), shape (frames + 2, height, width, 3): plane 0 holds what arrived "
                      "before start_ns, plane k + 1 what arrived in frame k, the last plane what arrived at or after end_ns; "
                      "the ambient term is not included";
    }
    j["start_opl"] = kSpeedOfLight * s.timeline.start_ns;  // metres: c · t
    j["bin_width_opl"] = kSpeedOfLight * s.timeline.delta();
    j["start_ns"] = s.timeline.start_ns;
    j["end_ns"] = s.timeline.end_ns;
    j["frames"] = s.timeline.frames;
    j["fps"] = s.fps;
    j["width"] = s.width;
    j["height"] = s.height;
    // Pixels that see a lamp directly, as [first pixel, count] runs (row-major, row 0 at the top):
    // retime leaves them out of the exposure, as render does.
    j["emitter_pixels"] = nlohmann::json::array();
    for (auto [first, count] : s.emitter_runs) j["emitter_pixels"].push_back({first, count});
    const std::string path = s.cube + ".json", temp = temp_sibling(path);
    {
        std::ofstream f(temp);
        f << j.dump(2) << "\n";
        if (!f) {
            discard_file(temp);
            throw RuntimeFailure("--cube " + path + ": cannot write");
        }
    }
    commit_file(temp, path);
}

}  // namespace

FrameOutputs::FrameOutputs(const OutputSettings& s) : settings_(s), exposure_(s.exposure) {
    if (!s.exr_dir.empty()) make_output_dir(s.exr_dir, "--exr-dir");
    if (!s.png_dir.empty()) make_output_dir(s.png_dir, "--png-dir");
    if (!s.video.empty()) {
        VideoSettings v;
        v.path = s.video;
        v.width = s.width;
        v.height = s.height;
        v.fps = s.fps;
        encoder_ = VideoEncoder::open(v);
    }
    if (!s.cube.empty() && s.cube_layout == CubeLayout::Slowlight)
        cube_ = std::make_unique<NpyCubeWriter>(s.cube, s.timeline.frames + 2, s.height, s.width);
    if (!s.cube.empty() && s.cube_layout == CubeLayout::Mitransient)
        cube_time_inner_ = std::make_unique<NpyTimeInnerWriter>(s.cube, s.timeline.frames, s.height, s.width);
    if (!s.hdf5.empty()) hdf5_ = std::make_unique<Hdf5CubeWriter>(s.hdf5, s.timeline, s.height, s.width);
    if (s.sensors.any()) sensors_ = std::make_unique<SensorImages>(s.sensors, s.timeline, s.width, s.height);
    if (s.label_time && (encoder_ || !s.png_dir.empty())) label_ = std::make_unique<TimeLabel>(s.width, s.height);
    rgb8_.resize(static_cast<size_t>(s.width) * s.height * 3);
    if (encoder_) encoding_.emplace();
}

std::string FrameOutputs::exr_frame_path(int index) const { return numbered(settings_.exr_dir, "exr", index); }
std::string FrameOutputs::exr_steady_path() const {
    return (std::filesystem::path(settings_.exr_dir) / "steady.exr").string();
}

void FrameOutputs::write_frame(int index, const std::vector<float>& rgb, bool on_disk, const Metadata& extra) {
    const int w = settings_.width, h = settings_.height;
    // The linear EXR and the tone-mapped outputs read the same frame and nothing else: the EXR
    // is written on another thread while this one tone-maps and encodes, so a run that asks
    // for both waits for the slower of the two, not their sum.
    tbb::task_group exr;
    if (!settings_.exr_dir.empty() && !on_disk)
        exr.run([&] {
            std::map<std::string, std::string> meta = settings_.metadata;
            for (const auto& [k, v] : extra) meta[k] = v;
            meta[kFrameIndexKey] = std::to_string(index);
            meta[kChecksumKey] = pixel_checksum(rgb.data(), rgb.size());  // --resume verifies it
            meta["slowlight:frame_start_ns"] = exact(settings_.timeline.edge(index));
            meta["slowlight:frame_end_ns"] = exact(settings_.timeline.edge(index + 1));
            // The exposure and curve the video and PNG frames were made with (linear data here).
            if (exposure_) meta["slowlight:exposure"] = exact(frame_exposure(index));
            meta["slowlight:tone"] = tone_name(settings_.tone);
            seconds_exr += timed([&] { write_exr(exr_frame_path(index), w, h, rgb.data(), meta); });
        });
    try {
        if (encoder_ || !settings_.png_dir.empty()) {
            tone_map_srgb8(rgb.data(), w, h, frame_exposure(index), rgb8_.data(), settings_.tone);
            if (label_)  // the time at the frame's end: everything up to then has arrived
                label_->burn(rgb8_.data(), format_frame_time(settings_.timeline.edge(index + 1), settings_.timeline.delta()));
            if (!settings_.png_dir.empty())
                seconds_png += timed([&] { write_png(numbered(settings_.png_dir, "png", index), w, h, rgb8_.data()); });
            if (encoder_) {
                try {
                    // Converted here, into the staging frame the encoder is not reading, while
                    // the frame before is still being encoded.
                    const int slot = staging_slot_;
                    staging_slot_ ^= 1;
                    const double convert_s = timed([&] { encoder_->convert(rgb8_.data(), slot); });
                    encoding_->wait();  // the frame before (rethrows its failure)
                    seconds_video += convert_s;
                    encoding_->run([this, slot] { seconds_video += timed([&] { encoder_->send(slot); }); });
                } catch (const RuntimeFailure&) {
                    drop_video(std::current_exception());
                }
            }
        }
    } catch (...) {
        exr.wait();  // the task reads rgb and this frame's settings: let it end first
        throw;
    }
    exr.wait();  // rethrows the EXR writer's failure, if any
    ++frames_written;
}

void FrameOutputs::write_steady(const std::vector<float>& rgb, const Metadata& extra) {
    const int w = settings_.width, h = settings_.height;
    if (!settings_.exr_dir.empty()) {
        std::map<std::string, std::string> meta = settings_.metadata;
        meta[kChecksumKey] = pixel_checksum(rgb.data(), rgb.size());
        for (const auto& [k, v] : extra) meta[k] = v;
        seconds_exr += timed([&] { write_exr(exr_steady_path(), w, h, rgb.data(), meta); });
    }
    if (!settings_.png_dir.empty()) {
        tone_map_srgb8(rgb.data(), w, h, exposure_.value_or(1.0), rgb8_.data(), settings_.tone);
        seconds_png += timed([&] { write_png((std::filesystem::path(settings_.png_dir) / "steady.png").string(), w, h, rgb8_.data()); });
    }
}

double FrameOutputs::frame_exposure(int index) const {
    if (index >= 0 && static_cast<size_t>(index) < per_frame_exposure_.size()) return per_frame_exposure_[index];
    return exposure_.value_or(1.0);
}

std::string FrameOutputs::summary() const {
    const std::string n = std::to_string(frames_written) + (frames_written == 1 ? " frame" : " frames");
    std::string s;
    auto add = [&](const std::string& what) { s += (s.empty() ? "" : ", ") + what; };
    if (encoder_) add((settings_.video == "-" ? std::string("YUV4MPEG2 to stdout") : settings_.video) + " (" + n + ")");
    if (!settings_.exr_dir.empty()) add(settings_.exr_dir + "/ (" + n + " as EXR, and steady.exr)");
    if (!settings_.png_dir.empty()) add(settings_.png_dir + "/ (" + n + " as PNG, and steady.png)");
    if ((cube_ || cube_time_inner_) && all_planes()) add(settings_.cube + " (the cube, and its .json)");
    if (hdf5_ && all_planes()) add(settings_.hdf5 + " (HDF5)");
    if (sensors_ && all_planes())
        add(std::to_string(SensorImages::file_names(settings_.sensors).size()) + " sensor images in " + settings_.exr_dir + "/");
    return s;
}

void FrameOutputs::write_cube_plane(const std::vector<float>& rgb) {
    if (!wants_cube()) return;  // (an MPI rank other than 0 writes nothing)
    const int plane = planes_seen_++, frames = settings_.timeline.frames;
    if (plane > frames + 1) throw RuntimeFailure("internal error: more cube planes than frames + 2");
    if (cube_) cube_->append(rgb.data());
    const bool before = plane == 0, after = plane == frames + 1;
    if (cube_time_inner_ && !before && !after) cube_time_inner_->append(rgb.data());
    if (hdf5_) {
        if (before) hdf5_->write_before(rgb.data());
        else if (after) hdf5_->write_after(rgb.data());
        else hdf5_->write_bin(plane - 1, rgb.data());
    }
    if (sensors_) {
        if (before) sensors_->add_before(rgb.data());
        else if (!after) sensors_->add_bin(plane - 1, rgb.data());
    }
}

// Once every bin went past: the sensor images, linear float EXRs beside the frames.
void FrameOutputs::write_sensor_images() {
    for (const SensorImage& img : sensors_->images()) {
        std::map<std::string, std::string> meta = settings_.metadata;
        for (const auto& [k, v] : img.metadata) meta[k] = v;
        seconds_exr += timed([&] {
            write_exr((std::filesystem::path(settings_.exr_dir) / img.file).string(), settings_.width,
                      settings_.height, img.rgb.data(), meta);
        });
    }
}

void FrameOutputs::drop_video(std::exception_ptr failure) {
    const bool others = !settings_.exr_dir.empty() || !settings_.png_dir.empty() || wants_cube();
    if (!others) std::rethrow_exception(failure);  // nothing else to deliver: stop now
    if (!video_failure_) video_failure_ = failure;
    try {
        encoding_->wait();  // idle before the encoder goes (a failure of its own says no more)
    } catch (const std::exception&) {
    }
    encoder_.reset();  // drops the video: its temporary removed, a pipe only closed
}

void FrameOutputs::finish() {
    try {
        if (encoding_ && encoder_) encoding_->wait();
        if (encoder_) seconds_video += timed([&] { encoder_->finish(); });
    } catch (const RuntimeFailure&) {
        drop_video(std::current_exception());
    }
    // Every plane went past unless Ctrl-C came before the last section (one never started has no bins).
    if (all_planes()) {
        if (cube_) cube_->finish();
        if (cube_time_inner_) cube_time_inner_->finish();
        if (cube_ || cube_time_inner_) write_cube_sidecar(settings_);
        if (hdf5_) {
            std::map<std::string, std::string> text = settings_.metadata;
            std::map<std::string, double> numbers{
                {"start_ns", settings_.timeline.start_ns}, {"end_ns", settings_.timeline.end_ns}, {"fps", settings_.fps}};
            if (exposure_) numbers["exposure"] = *exposure_;
            std::map<std::string, uint64_t> integers = settings_.integers;
            integers["frames"] = static_cast<uint64_t>(settings_.timeline.frames);
            hdf5_->finish(text, numbers, integers);
        }
        if (sensors_) write_sensor_images();
    }
    // The video's failure, once everything else is complete.
    if (video_failure_) std::rethrow_exception(std::exchange(video_failure_, nullptr));
}

}  // namespace sl
