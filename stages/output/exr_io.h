#pragma once
// Linear OpenEXR frames: float by default, because the numbers are analysed, not only viewed.
#include <map>
#include <string>
#include <vector>

namespace sl {

// Writes w*h interleaved RGB (row 0 = top) to `path` as an RGB scanline EXR, via a temporary
// sibling and a rename. `metadata` becomes string attributes in the header (e.g. a settings
// hash); `half` stores 16-bit channels instead of 32-bit float. Throws RuntimeFailure.
void write_exr(const std::string& path, int w, int h, const float* rgb,
               const std::map<std::string, std::string>& metadata = {}, bool half = false);

struct ExrImage {
    int width = 0, height = 0;
    std::vector<float> rgb;  // width*height*3, interleaved, row 0 = top of the data window
    std::map<std::string, std::string> metadata;  // every string attribute of the header
};

// Reads R, G, B (missing channels read as 0) as float. Throws RuntimeFailure.
ExrImage read_exr(const std::string& path);

// The header alone, so that a file can be judged before its pixels are allocated.
struct ExrHeaderInfo {
    int data_x0 = 0, data_y0 = 0, data_x1 = -1, data_y1 = -1;     // data window, inclusive
    int display_x0 = 0, display_y0 = 0, display_x1 = -1, display_y1 = -1;
    std::map<std::string, std::string> channels;  // name -> "half", "float" or "uint"
    std::map<std::string, std::string> metadata;  // every string attribute
    bool tiled = false;
};
ExrHeaderInfo read_exr_header(const std::string& path);  // Throws RuntimeFailure

}  // namespace sl
