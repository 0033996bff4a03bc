#pragma once
// A real decoder, for checking what the encoder wrote (tests of the output stage and the
// pipeline). Test-only: built into sl_test_support, which the program does not link.
#include <cstdint>
#include <string>
#include <vector>

namespace sl {

struct VideoInfo {
    int width = 0, height = 0;     // of the decoded frames
    double fps = 0;                // the stream's frame rate
    int64_t frames = 0;            // frames actually decoded, not the container's claim
    std::string codec;             // libavcodec name: "h264", "ffv1", "vp9", "rawvideo", ...
    std::vector<double> mean_luma; // per frame: mean of the stored 8-bit Y plane (0..255),
                                   // or of a gray conversion for RGB layouts
};

// Decodes every frame of the first video stream of `path`. Throws RuntimeFailure.
VideoInfo read_video(const std::string& path);

}  // namespace sl
