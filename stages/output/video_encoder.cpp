#include "stages/output/video_encoder.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/dict.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <atomic>
#include <cerrno>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "config/limits.h"
#include "foundation/errors.h"
#include "stages/output/atomic_file.h"
#include "stages/output/av_common.h"
#include "stages/output/sigpipe_block.h"

namespace sl {

namespace {

// What each accepted output name maps to.
struct Container {
    const char* ext;      // file extension, or "-" for stdout
    const char* muxer;    // libavformat short name
    const char* encoder;  // libavcodec encoder name
};

constexpr Container kContainers[] = {
    {".mp4", "mp4", "libx264"},
    {".mov", "mov", "libx264"},
    {".mkv", "matroska", "ffv1"},
    {".webm", "webm", "libvpx-vp9"},
    {"-", "yuv4mpegpipe", "wrapped_avframe"},  // the y4m muxer takes AVFrames, not rawvideo
};

const Container& container_for(const std::string& path) {
    std::string ext = path == "-" ? path : std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (const Container& c : kContainers)
        if (ext == c.ext) return c;
    // An existing device or FIFO without an extension (/dev/null, a named pipe): Matroska,
    // which streams without seeking back.
    std::error_code ec;
    auto st = std::filesystem::status(path, ec);
    if (ext.empty() && !ec && (st.type() == std::filesystem::file_type::character ||
                               st.type() == std::filesystem::file_type::fifo))
        return kContainers[2];
    throw InputError("-o " + path + ": unknown video container '" + ext +
                     "' (use .mp4, .mov, .mkv, .webm, - for stdout, or a device or FIFO)");
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

// Owns encoder options, so an InputError thrown while filling them does not leak.
struct Options {
    AVDictionary* dict = nullptr;
    Options() = default;
    Options(const Options&) = delete;
    Options& operator=(const Options&) = delete;
    ~Options() { av_dict_free(&dict); }
};

void set_option(AVDictionary** opts, const char* key, const std::string& value) {
    av_dict_set(opts, key, value.c_str(), 0);
}

// The crf to use: the codec's default, or the user's value checked against the codec's range.
int crf_for(const VideoSettings& vs, const char* encoder, int fallback, int max) {
    if (vs.quality < 0) return fallback;
    if (vs.quality > max)
        throw InputError("video quality (crf) " + std::to_string(vs.quality) +
                         " is out of range 0.." + std::to_string(max) + " for " + encoder);
    return vs.quality;
}

// Pixel format and private options per encoder.
AVPixelFormat configure_codec(const Container& c, const VideoSettings& vs, AVDictionary** opts) {
    const bool odd = vs.width % 2 != 0 || vs.height % 2 != 0;
    const std::string enc = c.encoder;
    if (enc == "libx264") {
        // veryfast: 192 frames at 512x512 took 0.59 s of CPU against fast's 1.35 s, for a file
        // as large at crf 18 (docs/benchmarks.md); with one section the encoder runs after the
        // render, so its time is the video's whole cost.
        set_option(opts, "preset", "veryfast");
        // A short look-ahead and one thread: x264 keeps every frame of its look-ahead and of
        // each frame thread (~2 MiB each at 512x512, 65 MiB with its defaults), all alive while
        // later sections render. One thread still encodes 512x512 at ~100 frames/s.
        set_option(opts, "rc-lookahead", "5");
        set_option(opts, "threads", "1");
        if (vs.lossless) {
            set_option(opts, "qp", "0");
            return AV_PIX_FMT_YUV444P;  // 4:2:0 would lose chroma
        }
        set_option(opts, "crf", std::to_string(crf_for(vs, c.encoder, 18, 51)));
        // x264's 4:2:0 needs even sizes; 4:4:4 (High 4:4:4 profile) keeps odd ones exact.
        return odd ? AV_PIX_FMT_YUV444P : AV_PIX_FMT_YUV420P;
    }
    if (enc == "libvpx-vp9") {
        // Good quality at a speed that keeps the encoder far from the renderer's cost.
        set_option(opts, "deadline", "good");
        set_option(opts, "cpu-used", "4");
        set_option(opts, "row-mt", "1");
        if (vs.lossless) {
            set_option(opts, "lossless", "1");
            return AV_PIX_FMT_YUV444P;
        }
        set_option(opts, "crf", std::to_string(crf_for(vs, c.encoder, 31, 63)));
        set_option(opts, "b", "0");  // crf with no bitrate cap = constant quality
        return AV_PIX_FMT_YUV420P;   // VP9's 4:2:0 handles odd sizes
    }
    if (enc == "ffv1") return AV_PIX_FMT_YUV444P;  // lossless codec: keep full chroma
    // y4m: 4:2:0 is what most consumers expect, 4:4:4 where the size is odd.
    return odd || vs.lossless ? AV_PIX_FMT_YUV444P : AV_PIX_FMT_YUV420P;
}

void check_settings(const VideoSettings& vs) {
    if (vs.width <= 0 || vs.height <= 0)
        throw InputError("video size " + std::to_string(vs.width) + "x" +
                         std::to_string(vs.height) + " must be positive");
    if (!(vs.fps >= limits::kMinFps && vs.fps <= limits::kMaxFps))
        throw InputError("video frame rate " + std::to_string(vs.fps) + " must be in " +
                         std::to_string(int(limits::kMinFps)) + ".." + std::to_string(int(limits::kMaxFps)));
}

}  // namespace

struct VideoEncoder::State {
    std::string path;     // what the user asked for ("-" for stdout)
    std::string target;   // where bytes go now: a temporary sibling, `path` itself, or pipe:1
    bool renamed_at_end = false;  // target is a temporary sibling of path

    AVFormatContext* fmt = nullptr;
    AVCodecContext* codec = nullptr;
    AVStream* stream = nullptr;
    SwsContext* sws = nullptr;
    // Two frames to convert into: one may be converted while the other is being encoded.
    AVFrame* staged[2] = {nullptr, nullptr};
    AVPacket* packet = nullptr;

    int width = 0, height = 0;
    int64_t frames = 0;
    bool finished = false;
    std::atomic<bool> failed{false};  // set by whichever thread meets the failure

    ~State() { release(); }

    std::string where() const { return path == "-" ? "stdout" : quoted(path); }

    [[noreturn]] void fail(const std::string& what, int err) {
        failed = true;
        throw RuntimeFailure(one_line("cannot write video " + where() + ": " + what + ": " +
                                      av_error_text(err)));
    }

    void check(int err, const char* what) {
        if (err < 0) fail(what, err);
    }

    // Frees everything; an unfinished temporary file is removed. Never throws.
    void release() noexcept {
        SigpipeBlock pipe_safe;  // closing flushes what is buffered
        if (fmt && fmt->pb && !(fmt->oformat->flags & AVFMT_NOFILE)) avio_closep(&fmt->pb);
        if (renamed_at_end) discard_file(target);
        renamed_at_end = false;
        sws_freeContext(sws);
        sws = nullptr;
        av_frame_free(&staged[0]);
        av_frame_free(&staged[1]);
        av_packet_free(&packet);
        avcodec_free_context(&codec);
        avformat_free_context(fmt);
        fmt = nullptr;
    }

    // Picks where the bytes go. Regular files are written beside the target and renamed;
    // existing special files (a FIFO, /dev/null) are written in place.
    void choose_target() {
        if (path == "-") {
            target = "pipe:1";  // libav's name for stdout
            return;
        }
        const OutputPlace place = place_output(path);
        if (place.directory)
            throw RuntimeFailure("cannot write video " + where() + ": is a directory");
        if (place.in_place) {
            target = path;
            return;
        }
        target = temp_sibling(path);
        renamed_at_end = true;
    }

    // Every call that may write runs under a SigpipeBlock (a pipe or FIFO whose reader is gone
    // must give EPIPE, not end the process); the writes happen on the calling thread.
    void open(const VideoSettings& vs) {
        SigpipeBlock pipe_safe;  // the header
        quiet_libav_logs();
        check_settings(vs);
        const Container& c = container_for(vs.path);
        const AVCodec* encoder = avcodec_find_encoder_by_name(c.encoder);
        if (!encoder)
            throw InputError("-o " + vs.path + ": this FFmpeg has no " + c.encoder + " encoder");

        path = vs.path;
        width = vs.width;
        height = vs.height;
        choose_target();

        check(avformat_alloc_output_context2(&fmt, nullptr, c.muxer, target.c_str()),
              "cannot create the container");
        stream = avformat_new_stream(fmt, nullptr);
        codec = avcodec_alloc_context3(encoder);
        staged[0] = av_frame_alloc();
        staged[1] = av_frame_alloc();
        packet = av_packet_alloc();
        if (!stream || !codec || !staged[0] || !staged[1] || !packet) fail("out of memory", AVERROR(ENOMEM));

        // Exact rate: pts counts frames, so the time base is the inverse of the frame rate.
        const AVRational rate = av_d2q(vs.fps, 100000);
        Options opts;
        codec->pix_fmt = configure_codec(c, vs, &opts.dict);
        codec->width = width;
        codec->height = height;
        codec->time_base = av_inv_q(rate);
        codec->framerate = rate;
        codec->sample_aspect_ratio = AVRational{1, 1};
        codec->color_primaries = AVCOL_PRI_BT709;
        codec->color_trc = AVCOL_TRC_BT709;
        codec->colorspace = AVCOL_SPC_BT709;
        codec->color_range = AVCOL_RANGE_MPEG;
        // swscale averages each 2x2 block of RGB into one chroma sample: centre siting.
        if (codec->pix_fmt == AV_PIX_FMT_YUV420P)
            codec->chroma_sample_location = AVCHROMA_LOC_CENTER;
        if (fmt->oformat->flags & AVFMT_GLOBALHEADER) codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;

        check(avcodec_open2(codec, encoder, &opts.dict), "cannot open the encoder");

        check(avcodec_parameters_from_context(stream->codecpar, codec),
              "cannot set stream parameters");
        stream->time_base = codec->time_base;  // a hint; the muxer may choose another
        stream->avg_frame_rate = rate;
        stream->r_frame_rate = rate;
        stream->sample_aspect_ratio = codec->sample_aspect_ratio;  // square pixels (y4m: A1:1)

        if (!(fmt->oformat->flags & AVFMT_NOFILE))
            check(avio_open(&fmt->pb, target.c_str(), AVIO_FLAG_WRITE), "cannot open for writing");
        check(avformat_write_header(fmt, nullptr), "cannot write the header");

        for (AVFrame* frame : staged) {
            frame->format = codec->pix_fmt;
            frame->width = width;
            frame->height = height;
            check(av_frame_get_buffer(frame, 0), "cannot allocate a frame");
            frame->color_primaries = codec->color_primaries;
            frame->color_trc = codec->color_trc;
            frame->colorspace = codec->colorspace;
            frame->color_range = codec->color_range;
            frame->sample_aspect_ratio = codec->sample_aspect_ratio;
        }

        // swscale defaults to BT.601; convert full-range RGB to limited-range BT.709 YUV.
        sws = sws_getContext(width, height, AV_PIX_FMT_RGB24, width, height, codec->pix_fmt,
                             SWS_BILINEAR | SWS_ACCURATE_RND, nullptr, nullptr, nullptr);
        if (!sws) fail("cannot create the colour converter", AVERROR(EINVAL));
        const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
        sws_setColorspaceDetails(sws, bt709, /*src full range*/ 1, bt709, /*dst limited*/ 0, 0,
                                 1 << 16, 1 << 16);
    }

    // Sends a frame (nullptr = flush) and writes every packet the encoder has ready.
    void encode(const AVFrame* f) {
        check(avcodec_send_frame(codec, f), "encoder rejected a frame");
        for (;;) {
            const int got = avcodec_receive_packet(codec, packet);
            if (got == AVERROR(EAGAIN) || got == AVERROR_EOF) return;
            check(got, "encoding failed");
            // One frame long, so muxers can time the last frame too.
            if (packet->duration == 0) packet->duration = 1;
            av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
            packet->stream_index = stream->index;
            check(av_interleaved_write_frame(fmt, packet), "write failed");  // unrefs packet
        }
    }

    // Touches only the colour converter and staged[slot]: it may run while the other slot
    // is being sent on another thread.
    void convert(const uint8_t* rgb8, int slot) {
        if (finished) throw std::logic_error("VideoEncoder::convert after finish");
        AVFrame* frame = staged[slot & 1];
        // The encoder (or wrapped_avframe) may still hold a reference to this slot's last buffer.
        check(av_frame_make_writable(frame), "cannot allocate a frame");
        const uint8_t* src[1] = {rgb8};
        const int stride[1] = {3 * width};
        sws_scale(sws, src, stride, 0, height, frame->data, frame->linesize);
    }

    void send(int slot) {
        if (finished) throw std::logic_error("VideoEncoder::send after finish");
        if (failed)
            throw RuntimeFailure("cannot write video " + where() + ": the encoder failed earlier");
        SigpipeBlock pipe_safe;
        AVFrame* frame = staged[slot & 1];
        frame->pts = frames;
        encode(frame);
        ++frames;
    }

    void finish() {
        if (finished) return;
        finished = true;
        SigpipeBlock pipe_safe;  // the last packets, the trailer, the final flush
        // A half-written stream cannot be finished, and a file with no frame is no video: drop.
        if (failed || (frames == 0 && renamed_at_end)) {
            release();
            return;
        }
        try {
            encode(nullptr);
            check(av_write_trailer(fmt), "cannot write the trailer");
            if (fmt->pb) {
                // avio_close does not report a failed final flush, so flush and look first.
                avio_flush(fmt->pb);
                check(fmt->pb->error, "write failed");
                if (!(fmt->oformat->flags & AVFMT_NOFILE))
                    check(avio_closep(&fmt->pb), "close failed");
            }
            if (renamed_at_end) {
                renamed_at_end = false;
                commit_file(target, path);
            }
        } catch (...) {
            failed = true;
            release();
            throw;
        }
        release();
    }
};

VideoEncoder::VideoEncoder(std::unique_ptr<State> state) : s_(std::move(state)) {}

std::unique_ptr<VideoEncoder> VideoEncoder::open(const VideoSettings& settings) {
    auto state = std::make_unique<State>();
    state->open(settings);  // on a throw, ~State frees what was made and removes the temp file
    return std::unique_ptr<VideoEncoder>(new VideoEncoder(std::move(state)));
}

void VideoEncoder::write_frame(const uint8_t* rgb8) {
    s_->convert(rgb8, 0);
    s_->send(0);
}

void VideoEncoder::convert(const uint8_t* rgb8, int slot) { s_->convert(rgb8, slot); }

void VideoEncoder::send(int slot) { s_->send(slot); }

void VideoEncoder::finish() { s_->finish(); }

VideoEncoder::~VideoEncoder() {
    // Not finished: the run failed. A shortened video that plays would look whole, so the
    // temporary file is removed (a device or FIFO written in place is only closed).
    s_->release();
}

int64_t VideoEncoder::frames_written() const { return s_->frames; }

}  // namespace sl
