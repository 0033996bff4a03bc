#include "stages/output/time_label.h"

extern "C" {
#include <libavfilter/avfilter.h>
#include <libavfilter/buffersink.h>
#include <libavfilter/buffersrc.h>
#include <libavutil/dict.h>
#include <libavutil/frame.h>
#include <libavutil/opt.h>
}

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/errors.h"
#include "stages/output/av_common.h"

namespace sl {

// The font: DejaVu Sans where Debian's fonts-dejavu-core puts it, else whatever fontconfig
// calls "Sans".
static const char* const kFontFiles[] = {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
                                          "/usr/share/fonts/TTF/DejaVuSans.ttf",
                                          "/usr/share/fonts/dejavu/DejaVuSans.ttf"};

struct TimeLabel::Graph {
    AVFilterGraph* graph = nullptr;
    AVFilterContext* source = nullptr;
    AVFilterContext* sink = nullptr;
    AVFrame* in = nullptr;
    AVFrame* out = nullptr;
    ~Graph() {
        av_frame_free(&in);
        av_frame_free(&out);
        avfilter_graph_free(&graph);
    }
};

namespace {

[[noreturn]] void fail(const std::string& what, int err = 0) {
    throw RuntimeFailure("--label: " + what + (err ? ": " + av_error_text(err) : std::string()));
}

void check(int err, const char* what) {
    if (err < 0) fail(what, err);
}

}  // namespace

TimeLabel::TimeLabel(int width, int height) : graph_(std::make_unique<Graph>()), width_(width), height_(height) {
    quiet_libav_logs();
    Graph& g = *graph_;
    g.graph = avfilter_graph_alloc();
    if (!g.graph) fail("out of memory");
    const AVFilter* buffer = avfilter_get_by_name("buffer");
    const AVFilter* sink = avfilter_get_by_name("buffersink");
    const AVFilter* drawtext = avfilter_get_by_name("drawtext");
    if (!buffer || !sink || !drawtext) fail("this FFmpeg's libavfilter has no drawtext filter");

    char args[160];
    std::snprintf(args, sizeof args, "video_size=%dx%d:pix_fmt=%d:time_base=1/25:pixel_aspect=1/1", width, height,
                  static_cast<int>(AV_PIX_FMT_RGB24));
    check(avfilter_graph_create_filter(&g.source, buffer, "in", args, nullptr, g.graph), "buffer source");
    check(avfilter_graph_create_filter(&g.sink, sink, "out", nullptr, nullptr, g.graph), "buffer sink");
    const enum AVPixelFormat formats[] = {AV_PIX_FMT_RGB24, AV_PIX_FMT_NONE};
    check(av_opt_set_int_list(g.sink, "pix_fmts", formats, AV_PIX_FMT_NONE, AV_OPT_SEARCH_CHILDREN), "sink format");

    // Options set one by one: no filter-graph string, so nothing needs escaping.
    AVFilterContext* text = avfilter_graph_alloc_filter(g.graph, drawtext, "label");
    if (!text) fail("cannot create drawtext");
    std::string font;
    for (const char* f : kFontFiles)
        if (std::filesystem::exists(f)) {
            font = f;
            break;
        }
    if (!font.empty()) check(av_opt_set(text, "fontfile", font.c_str(), AV_OPT_SEARCH_CHILDREN), "fontfile");
    else check(av_opt_set(text, "font", "Sans", AV_OPT_SEARCH_CHILDREN), "font");
    const int size = std::max(10, height / 14), margin = std::max(4, height / 40);
    check(av_opt_set(text, "text", "%{metadata:slowlight_label}", AV_OPT_SEARCH_CHILDREN), "text");
    check(av_opt_set(text, "fontsize", std::to_string(size).c_str(), AV_OPT_SEARCH_CHILDREN), "fontsize");
    check(av_opt_set(text, "fontcolor", "white", AV_OPT_SEARCH_CHILDREN), "fontcolor");
    check(av_opt_set_int(text, "box", 1, AV_OPT_SEARCH_CHILDREN), "box");
    check(av_opt_set(text, "boxcolor", "black@0.6", AV_OPT_SEARCH_CHILDREN), "boxcolor");
    check(av_opt_set_int(text, "boxborderw", std::max(2, size / 5), AV_OPT_SEARCH_CHILDREN), "boxborderw");
    check(av_opt_set(text, "x", std::to_string(margin).c_str(), AV_OPT_SEARCH_CHILDREN), "x");
    check(av_opt_set(text, "y", ("h-th-" + std::to_string(margin)).c_str(), AV_OPT_SEARCH_CHILDREN), "y");
    check(avfilter_init_str(text, nullptr), "drawtext (is a font installed? Debian: fonts-dejavu-core)");

    check(avfilter_link(g.source, 0, text, 0), "link");
    check(avfilter_link(text, 0, g.sink, 0), "link");
    check(avfilter_graph_config(g.graph, nullptr), "filter graph");

    g.in = av_frame_alloc();
    g.out = av_frame_alloc();
    if (!g.in || !g.out) fail("out of memory");
}

TimeLabel::~TimeLabel() = default;

void TimeLabel::burn(uint8_t* rgb8, const std::string& label) {
    Graph& g = *graph_;
    av_frame_unref(g.in);
    g.in->format = AV_PIX_FMT_RGB24;
    g.in->width = width_;
    g.in->height = height_;
    g.in->pts = pts_++;
    check(av_frame_get_buffer(g.in, 0), "frame");
    const size_t row = static_cast<size_t>(width_) * 3;
    for (int y = 0; y < height_; ++y) std::memcpy(g.in->data[0] + y * g.in->linesize[0], rgb8 + y * row, row);
    av_dict_set(&g.in->metadata, "slowlight_label", label.c_str(), 0);
    check(av_buffersrc_add_frame_flags(g.source, g.in, AV_BUFFERSRC_FLAG_KEEP_REF), "send frame");
    av_frame_unref(g.out);
    check(av_buffersink_get_frame(g.sink, g.out), "receive frame");
    for (int y = 0; y < height_; ++y) std::memcpy(rgb8 + y * row, g.out->data[0] + y * g.out->linesize[0], row);
    av_frame_unref(g.out);
}

std::string format_frame_time(double t_ns, double delta_ns) {
    double value = t_ns, step = delta_ns;
    const char* unit = "ns";
    if (std::abs(t_ns) < 1 && delta_ns < 1) {
        value *= 1000;
        step *= 1000;
        unit = "ps";
    } else if (std::abs(t_ns) >= 10000) {
        value /= 1000;
        step /= 1000;
        unit = "\u00b5s";
    }
    // As many decimals as the frame times need: 0.5 ns steps get one, 0.25 two, 1/3 three.
    int decimals = 0;
    while (decimals < 3 && std::abs(step * std::pow(10.0, decimals) - std::round(step * std::pow(10.0, decimals))) >
                               1e-6 * std::max(1.0, step * std::pow(10.0, decimals)))
        ++decimals;
    char buf[64];
    std::snprintf(buf, sizeof buf, "t = %.*f %s", decimals, value, unit);
    return buf;
}

}  // namespace sl
