#include "tests/common/video_reader.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/pixdesc.h>
#include <libswscale/swscale.h>
}

#include <cstddef>
#include <memory>

#include "foundation/errors.h"
#include "stages/output/atomic_file.h"
#include "stages/output/av_common.h"

namespace sl {

namespace {

// Owners for the libav objects, so every exit path frees them.
struct InputCloser {
    void operator()(AVFormatContext* p) const { avformat_close_input(&p); }
};
struct CodecFreer {
    void operator()(AVCodecContext* p) const { avcodec_free_context(&p); }
};
struct FrameFreer {
    void operator()(AVFrame* p) const { av_frame_free(&p); }
};
struct PacketFreer {
    void operator()(AVPacket* p) const { av_packet_free(&p); }
};
struct SwsFreer {
    void operator()(SwsContext* p) const { sws_freeContext(p); }
};

class Decoder {
public:
    explicit Decoder(const std::string& path) : path_(path) {}

    VideoInfo run() {
        quiet_libav_logs();
        AVFormatContext* raw = nullptr;
        check(avformat_open_input(&raw, path_.c_str(), nullptr, nullptr), "cannot open");
        fmt_.reset(raw);
        check(avformat_find_stream_info(fmt_.get(), nullptr), "cannot read stream info");

        const AVCodec* decoder = nullptr;
        stream_ = av_find_best_stream(fmt_.get(), AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
        check(stream_, "no video stream");
        AVStream* st = fmt_->streams[stream_];

        codec_.reset(avcodec_alloc_context3(decoder));
        frame_.reset(av_frame_alloc());
        packet_.reset(av_packet_alloc());
        if (!codec_ || !frame_ || !packet_) check(AVERROR(ENOMEM), "out of memory");
        check(avcodec_parameters_to_context(codec_.get(), st->codecpar), "bad stream parameters");
        check(avcodec_open2(codec_.get(), decoder, nullptr), "cannot open the decoder");

        info_.codec = avcodec_get_name(st->codecpar->codec_id);
        info_.width = st->codecpar->width;
        info_.height = st->codecpar->height;
        info_.fps = av_q2d(av_guess_frame_rate(fmt_.get(), st, nullptr));

        for (;;) {
            const int got = av_read_frame(fmt_.get(), packet_.get());
            if (got == AVERROR_EOF) break;
            check(got, "read failed");
            if (packet_->stream_index == stream_) decode(packet_.get());
            av_packet_unref(packet_.get());
        }
        decode(nullptr);  // drain frames the decoder still holds
        return std::move(info_);
    }

private:
    void check(int err, const char* what) const {
        if (err < 0)
            throw RuntimeFailure(one_line("cannot read video '" + path_ + "': " + what + ": " +
                                          av_error_text(err)));
    }

    void decode(const AVPacket* pkt) {
        check(avcodec_send_packet(codec_.get(), pkt), "decoder rejected a packet");
        for (;;) {
            const int got = avcodec_receive_frame(codec_.get(), frame_.get());
            if (got == AVERROR(EAGAIN) || got == AVERROR_EOF) return;
            check(got, "decoding failed");
            info_.width = frame_->width;
            info_.height = frame_->height;
            info_.mean_luma.push_back(mean_luma(frame_.get()));
            ++info_.frames;
            av_frame_unref(frame_.get());
        }
    }

    // Mean of the stored 8-bit Y plane; other layouts (RGB, packed, deeper) via swscale gray.
    double mean_luma(const AVFrame* f) {
        const AVPixFmtDescriptor* d = av_pix_fmt_desc_get(AVPixelFormat(f->format));
        const bool planar_y8 = d && (d->flags & AV_PIX_FMT_FLAG_PLANAR) &&
                               !(d->flags & AV_PIX_FMT_FLAG_RGB) && d->comp[0].plane == 0 &&
                               d->comp[0].depth == 8 && d->comp[0].step == 1;
        if (planar_y8) return mean_of(f->data[0], f->linesize[0], f->width, f->height);

        sws_.reset(sws_getCachedContext(sws_.release(), f->width, f->height,
                                        AVPixelFormat(f->format), f->width, f->height,
                                        AV_PIX_FMT_GRAY8, SWS_POINT, nullptr, nullptr, nullptr));
        if (!sws_) check(AVERROR(EINVAL), "cannot convert to gray");
        gray_.resize(size_t(f->width) * size_t(f->height));
        uint8_t* dst[1] = {gray_.data()};
        const int stride[1] = {f->width};
        sws_scale(sws_.get(), f->data, f->linesize, 0, f->height, dst, stride);
        return mean_of(gray_.data(), f->width, f->width, f->height);
    }

    static double mean_of(const uint8_t* plane, int stride, int w, int h) {
        uint64_t sum = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) sum += plane[ptrdiff_t(y) * stride + x];
        return w > 0 && h > 0 ? double(sum) / (double(w) * double(h)) : 0.0;
    }

    std::string path_;
    std::unique_ptr<AVFormatContext, InputCloser> fmt_;
    std::unique_ptr<AVCodecContext, CodecFreer> codec_;
    std::unique_ptr<AVFrame, FrameFreer> frame_;
    std::unique_ptr<AVPacket, PacketFreer> packet_;
    std::unique_ptr<SwsContext, SwsFreer> sws_;
    std::vector<uint8_t> gray_;
    int stream_ = -1;
    VideoInfo info_;
};

}  // namespace

VideoInfo read_video(const std::string& path) { return Decoder(path).run(); }

}  // namespace sl
