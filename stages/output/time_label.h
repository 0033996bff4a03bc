#pragma once
// --label time: the frame's time written onto 8-bit RGB frames by FFmpeg's own text filter
// (libavfilter's drawtext: FreeType glyphs, DejaVu Sans), in a dark box at the bottom left. The
// filter lives in a plugin (plugins/label_drawtext) loaded on first use.
#include <cstdint>
#include <memory>
#include <string>

namespace sl {

class TimeLabel {
public:
    // Throws RuntimeFailure when libavfilter has no drawtext or no font is found.
    TimeLabel(int width, int height);
    ~TimeLabel();
    TimeLabel(const TimeLabel&) = delete;
    TimeLabel& operator=(const TimeLabel&) = delete;

    // Draws `text` onto the w*h*3 frame, in place.
    void burn(uint8_t* rgb8, const std::string& text);

    struct Graph;

private:
    std::unique_ptr<Graph> graph_;
    int width_, height_;
};

// "t = 3.50 ns": a time in the unit that suits the window (ps below 1 ns, µs from 10000 ns),
// with as many decimals as the frame width `delta_ns` needs (at most three).
std::string format_frame_time(double t_ns, double delta_ns);

}  // namespace sl
