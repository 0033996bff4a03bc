#pragma once
// Linear radiance -> display: one exposure for the whole video, then the sRGB curve.
// Images are interleaved linear float RGB, row 0 at the top, w*h*3 values.
#include <cstdint>

namespace sl {

// The linear multiplier that maps the 99th percentile of pixel luminance (Rec.709 weights) to
// 1.0. Non-finite pixels are ignored; if the percentile is 0 the maximum is used instead; if
// every pixel is 0 (or none is finite) the result is 1.
double exposure_from_steady(const float* rgb, int w, int h);

// out = round(255 * sRGB_OETF(clamp(exposure * rgb, 0, 1))); NaN becomes 0.
void tone_map_srgb8(const float* rgb, int w, int h, double exposure, uint8_t* out_rgb8);

}  // namespace sl
