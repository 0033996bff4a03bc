// The --label time writer, a plugin loaded only when a label is asked for: libavfilter brings
// dozens of shared libraries (FreeType, fontconfig, and every filter's own) that a render
// without --label never needs. Text goes through FFmpeg's own drawtext filter.
#include <cstdint>

extern "C" {
#include <libavfilter/avfilter.h>
#include <libavfilter/buffersink.h>
#include <libavfilter/buffersrc.h>
#include <libavutil/dict.h>
#include <libavutil/error.h>
#include <libavutil/frame.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
}

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace {

// The font: DejaVu Sans where Debian's fonts-dejavu-core puts it, else whatever fontconfig
// calls "Sans".
const char* const kFontFiles[] = {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
                                  "/usr/share/fonts/TTF/DejaVuSans.ttf", "/usr/share/fonts/dejavu/DejaVuSans.ttf"};

struct Label {
    AVFilterGraph* graph = nullptr;
    AVFilterContext* source = nullptr;
    AVFilterContext* sink = nullptr;
    AVFrame* in = nullptr;
    AVFrame* out = nullptr;
    int width = 0, height = 0;
    int64_t pts = 0;
    ~Label() {
        av_frame_free(&in);
        av_frame_free(&out);
        avfilter_graph_free(&graph);
    }
};

void check(int err, const char* what) {
    if (err >= 0) return;
    char text[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(err, text, sizeof text);
    throw std::runtime_error(std::string(what) + ": " + text);
}

void copy_error(const std::string& why, char* error, size_t size) {
    if (size == 0) return;
    std::strncpy(error, why.c_str(), size - 1);
    error[size - 1] = '\0';
}

void build(Label& g, int width, int height) {
    av_log_set_level(AV_LOG_ERROR);
    g.width = width;
    g.height = height;
    g.graph = avfilter_graph_alloc();
    if (!g.graph) throw std::runtime_error("out of memory");
    const AVFilter* buffer = avfilter_get_by_name("buffer");
    const AVFilter* sink = avfilter_get_by_name("buffersink");
    const AVFilter* drawtext = avfilter_get_by_name("drawtext");
    if (!buffer || !sink || !drawtext) throw std::runtime_error("this FFmpeg's libavfilter has no drawtext filter");

    char args[160];
    std::snprintf(args, sizeof args, "video_size=%dx%d:pix_fmt=%d:time_base=1/25:pixel_aspect=1/1", width, height,
                  static_cast<int>(AV_PIX_FMT_RGB24));
    check(avfilter_graph_create_filter(&g.source, buffer, "in", args, nullptr, g.graph), "buffer source");
    check(avfilter_graph_create_filter(&g.sink, sink, "out", nullptr, nullptr, g.graph), "buffer sink");
    const enum AVPixelFormat formats[] = {AV_PIX_FMT_RGB24, AV_PIX_FMT_NONE};
    check(av_opt_set_int_list(g.sink, "pix_fmts", formats, AV_PIX_FMT_NONE, AV_OPT_SEARCH_CHILDREN), "sink format");

    // Options set one by one: no filter-graph string, so nothing needs escaping.
    AVFilterContext* text = avfilter_graph_alloc_filter(g.graph, drawtext, "label");
    if (!text) throw std::runtime_error("cannot create drawtext");
    std::string font;
    for (const char* f : kFontFiles)
        if (std::filesystem::exists(f)) {
            font = f;
            break;
        }
    if (!font.empty()) check(av_opt_set(text, "fontfile", font.c_str(), AV_OPT_SEARCH_CHILDREN), "fontfile");
    else check(av_opt_set(text, "font", "Sans", AV_OPT_SEARCH_CHILDREN), "font");
    const int size = std::max(10, height / 14), margin = std::max(4, height / 40);
    // The frame's text arrives as frame metadata, so one graph serves every frame.
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
    if (!g.in || !g.out) throw std::runtime_error("out of memory");
}

void burn(Label& g, unsigned char* rgb8, const char* label) {
    av_frame_unref(g.in);
    g.in->format = AV_PIX_FMT_RGB24;
    g.in->width = g.width;
    g.in->height = g.height;
    g.in->pts = g.pts++;
    check(av_frame_get_buffer(g.in, 0), "frame");
    const size_t row = static_cast<size_t>(g.width) * 3;
    for (int y = 0; y < g.height; ++y) std::memcpy(g.in->data[0] + y * g.in->linesize[0], rgb8 + y * row, row);
    av_dict_set(&g.in->metadata, "slowlight_label", label, 0);
    check(av_buffersrc_add_frame_flags(g.source, g.in, AV_BUFFERSRC_FLAG_KEEP_REF), "send frame");
    av_frame_unref(g.out);
    check(av_buffersink_get_frame(g.sink, g.out), "receive frame");
    for (int y = 0; y < g.height; ++y) std::memcpy(rgb8 + y * row, g.out->data[0] + y * g.out->linesize[0], row);
    av_frame_unref(g.out);
}

}  // namespace

#define SL_EXPORT extern "C" __attribute__((visibility("default")))

// A labeller for w x h RGB frames, or null with a message.
SL_EXPORT void* slowlight_label_open(int width, int height, char* error, size_t error_size) {
    Label* g = new Label;
    try {
        build(*g, width, height);
        return g;
    } catch (const std::exception& e) {
        copy_error(e.what(), error, error_size);
        delete g;
        return nullptr;
    }
}

// Draws `text` onto the w*h*3 frame, in place. Returns 1, or 0 with a message.
SL_EXPORT int slowlight_label_burn(void* label, unsigned char* rgb8, const char* text, char* error, size_t error_size) {
    try {
        burn(*static_cast<Label*>(label), rgb8, text);
        return 1;
    } catch (const std::exception& e) {
        copy_error(e.what(), error, error_size);
        return 0;
    }
}

SL_EXPORT void slowlight_label_close(void* label) { delete static_cast<Label*>(label); }
