#pragma once
// The header of an EXR frame, walked in the file's own bytes before OpenEXR sees it.
//
// OpenEXR sizes its tables and line buffers from the header before any check of ours could run:
// a forged file declaring a wide data window, many channels or a tiled layout makes the library
// allocate gigabytes while merely opening it. Every file this program reads back it wrote itself
// (one part, scanlines, channels R, G, B of half or float, both windows equal), so anything else
// is refused here, and with an expected size the windows must be that size: then nothing OpenEXR
// allocates can exceed what the render itself holds. Found by fuzzing --resume's reader.
#include <map>
#include <string>

namespace sl {

// What a header says, read without OpenEXR.
struct ExrHeaderInfo {
    int data_x0 = 0, data_y0 = 0, data_x1 = -1, data_y1 = -1;     // data window, inclusive
    int display_x0 = 0, display_y0 = 0, display_x1 = -1, display_y1 = -1;
    std::map<std::string, std::string> channels;  // name -> "half" or "float"
    std::map<std::string, std::string> metadata;  // every string attribute
};

// Throws RuntimeFailure("<label>: <what is wrong>") when the header is not single-part scanline,
// has channels other than R, G, B of half or float, or an attribute twice or past the end.
// `label` names the file for the reader ("cannot read EXR 'x.exr'" when empty).
ExrHeaderInfo scan_exr_header(const std::string& path, const std::string& label = "");

struct ExrSize {
    int width = 0, height = 0;  // 0 x 0: any size up to the limits below
};
inline constexpr long long kMaxExrPixels = 1ll << 26, kMaxExrWidth = 1ll << 16;

// Throws RuntimeFailure unless both windows are `want` at (0, 0) (or, without `want`, within the
// limits above): called before OpenEXR opens the file.
void require_exr_size(const std::string& path, const ExrHeaderInfo& h, ExrSize want, const std::string& label = "");

}  // namespace sl
