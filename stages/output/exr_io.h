#pragma once
// Linear OpenEXR frames: float by default, because the numbers are analysed, not only viewed.
#include <map>
#include <string>
#include <vector>

#include "stages/output/exr_header_scan.h"

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

// Reads R, G, B (missing channels read as 0) as float. Only frames shaped as this program writes
// them are opened (exr_header_scan.h); with `want`, only that size. Throws RuntimeFailure.
ExrImage read_exr(const std::string& path, ExrSize want = {});

}  // namespace sl
