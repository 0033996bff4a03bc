#pragma once
// Encodes 8-bit sRGB frames into a video file, or YUV4MPEG2 on stdout.
//
//   .mp4 / .mov  H.264 (libx264), yuv420p, crf 18 by default
//   .mkv         FFV1, lossless codec, yuv444p
//   .webm        VP9 (libvpx-vp9), yuv420p, constant quality
//   -            YUV4MPEG2 on stdout (uncompressed, for piping into other tools)
//
// Colours are converted with BT.709 coefficients to limited range and tagged so. Where 4:2:0
// cannot hold an odd width/height (H.264, y4m) the frames are stored 4:4:4 instead, so the
// decoded size is always the requested one. A file is written under a temporary name and
// renamed on finish(), so a failed run never leaves a truncated file that looks whole (an
// interrupted run calls finish() on purpose: its video plays). A symbolic link is written
// through to its target; a device or FIFO is written in place (see atomic_file.h).
#include <cstdint>
#include <memory>
#include <string>

namespace sl {

struct VideoSettings {
    std::string path;          // by extension (see above), or "-" for stdout
    int width = 0, height = 0;
    double fps = 24;           // exact: 29.97 is stored as 2997/100
    int quality = -1;          // crf; -1 = codec default (x264 0..51, VP9 0..63; FFV1 ignores it)
    bool lossless = false;     // .mp4/.mov/.webm: lossless 4:4:4; .mkv is always lossless
};

class VideoEncoder {
public:
    // Every check happens here, before any rendering: InputError for a bad setting, an unknown
    // extension or an encoder this FFmpeg lacks; RuntimeFailure when the output cannot be
    // opened (missing directory, a directory, not writable). A pipe or FIFO whose reader is
    // gone gives a RuntimeFailure from the call that wrote, not SIGPIPE: each call that may
    // write blocks SIGPIPE in its own thread while it does (sigpipe_block.h); the process's
    // disposition of SIGPIPE is never changed.
    static std::unique_ptr<VideoEncoder> open(const VideoSettings& settings);

    // One frame of width*height*3 sRGB bytes, row 0 = top, in presentation order.
    // Throws RuntimeFailure on an encoder or write error (e.g. EPIPE); the output is then
    // abandoned (the temporary file removed) rather than finished.
    void write_frame(const uint8_t* rgb8);
    // write_frame() in two steps, for a caller that converts the next frame to the codec's
    // format while the last one is encoded on another thread: convert() fills staging frame
    // `slot` (0 or 1) from rgb8, send() encodes it. One thread converts, one sends; a slot is
    // never converted into while it is being sent.
    void convert(const uint8_t* rgb8, int slot);
    void send(int slot);

    // Flushes the encoder, writes the trailer, closes and renames into place. Idempotent.
    void finish();

    // Without finish() (an error unwinding), the video is dropped: its temporary file is
    // removed, so nothing at the final name looks whole. Never throws.
    ~VideoEncoder();

    int64_t frames_written() const;

    VideoEncoder(const VideoEncoder&) = delete;
    VideoEncoder& operator=(const VideoEncoder&) = delete;

private:
    struct State;  // libav objects, kept out of this header
    explicit VideoEncoder(std::unique_ptr<State> state);
    std::unique_ptr<State> s_;
};

}  // namespace sl
