#pragma once
// Tone-mapped 8-bit frames for quick looks.
#include <cstdint>
#include <string>

namespace sl {

// Writes w*h interleaved sRGB bytes (row 0 = top) as a PNG, via a temporary sibling and a
// rename. Throws RuntimeFailure naming the path.
void write_png(const std::string& path, int w, int h, const uint8_t* rgb8);

}  // namespace sl
