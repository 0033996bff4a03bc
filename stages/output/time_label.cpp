#include "stages/output/time_label.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/plugin.h"
#include "foundation/errors.h"

namespace sl {

// The drawtext plugin, libslowlight_label.so, beside the executable (or on the library path),
// loaded on first use: libavfilter's many libraries stay out of renders without --label.
struct TimeLabel::Graph {
    using OpenFn = void* (*)(int, int, char*, size_t);
    using BurnFn = int (*)(void*, unsigned char*, const char*, char*, size_t);
    using CloseFn = void (*)(void*);
    OpenFn open = nullptr;
    BurnFn burn = nullptr;
    CloseFn close = nullptr;
    void* handle = nullptr;
    ~Graph() {
        if (handle && close) close(handle);
    }
};

TimeLabel::TimeLabel(int width, int height) : graph_(std::make_unique<Graph>()), width_(width), height_(height) {
    static const Plugin plugin = load_plugin("libslowlight_label.so", "the label writer",
                                             {"slowlight_label_open", "slowlight_label_burn", "slowlight_label_close"});
    if (!plugin.error.empty()) throw RuntimeFailure("--label: " + plugin.error);
    Graph& g = *graph_;
    g.open = plugin.function<Graph::OpenFn>(0);
    g.burn = plugin.function<Graph::BurnFn>(1);
    g.close = plugin.function<Graph::CloseFn>(2);
    char error[512] = {};
    g.handle = g.open(width, height, error, sizeof error);
    if (!g.handle) throw RuntimeFailure(std::string("--label: ") + error);
}

TimeLabel::~TimeLabel() = default;

void TimeLabel::burn(uint8_t* rgb8, const std::string& label) {
    char error[512] = {};
    if (!graph_->burn(graph_->handle, rgb8, label.c_str(), error, sizeof error))
        throw RuntimeFailure(std::string("--label: ") + error);
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
