#include "pipeline/frame_outputs.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "core/errors.h"
#include "stages/output/exr_io.h"
#include "stages/output/png_io.h"
#include "stages/output/tone_map.h"

namespace sl {
namespace {

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
    rgb8_.resize(static_cast<size_t>(s.width) * s.height * 3);
}

void FrameOutputs::write_frame(int index, const std::vector<float>& rgb) {
    const int w = settings_.width, h = settings_.height;
    if (!settings_.exr_dir.empty())
        seconds_exr += timed([&] { write_exr(numbered(settings_.exr_dir, "exr", index), w, h, rgb.data(), settings_.metadata); });
    if (encoder_ || !settings_.png_dir.empty()) {
        tone_map_srgb8(rgb.data(), w, h, exposure_.value_or(1.0), rgb8_.data());
        if (!settings_.png_dir.empty())
            seconds_png += timed([&] { write_png(numbered(settings_.png_dir, "png", index), w, h, rgb8_.data()); });
        if (encoder_) seconds_video += timed([&] { encoder_->write_frame(rgb8_.data()); });
    }
    ++frames_written;
}

void FrameOutputs::write_steady(const std::vector<float>& rgb) {
    const int w = settings_.width, h = settings_.height;
    if (!settings_.exr_dir.empty())
        seconds_exr += timed([&] {
            write_exr((std::filesystem::path(settings_.exr_dir) / "steady.exr").string(), w, h, rgb.data(), settings_.metadata);
        });
    if (!settings_.png_dir.empty()) {
        tone_map_srgb8(rgb.data(), w, h, exposure_.value_or(1.0), rgb8_.data());
        seconds_png += timed([&] { write_png((std::filesystem::path(settings_.png_dir) / "steady.png").string(), w, h, rgb8_.data()); });
    }
}

void FrameOutputs::finish() {
    if (encoder_) seconds_video += timed([&] { encoder_->finish(); });
}

}  // namespace sl
