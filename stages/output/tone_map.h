#pragma once
// Linear radiance -> display: one exposure for the whole video, then the sRGB curve.
// Images are interleaved linear float RGB, row 0 at the top, w*h*3 values.
#include <cstdint>

#include "config/run_options.h"

namespace sl {

// The linear multiplier that maps the 99th percentile of pixel luminance (Rec.709 weights) to
// 1.0. Non-finite pixels are ignored; if the percentile is 0 the maximum is used instead; if
// every pixel is 0 (or none is finite) the result is 1.
double exposure_from_steady(const float* rgb, int w, int h);

// out = round(255 * sRGB_OETF(curve(exposure * rgb))) per channel; NaN becomes 0. The curves,
// all 0 at 0 and reaching white (1) where stated:
//   linear  clamp(v, 0, 1): white at v = 1, everything brighter clipped;
//   filmic  the ACES fit of Narkowicz (2015), v(2.51v + 0.03) / (v(2.43v + 0.59) + 0.14): a toe,
//           a soft shoulder, white at v ~ 5.5 (mid greys a little darker than linear);
//   log     ln(1 + 16v) / ln(1 + 16 * 4): the darks lifted, white at v = 4.
void tone_map_srgb8(const float* rgb, int w, int h, double exposure, uint8_t* out_rgb8,
                    ToneCurve curve = ToneCurve::Linear);

// The curve alone, for one exposed value (what tone_map_srgb8 applies before the sRGB encoding).
double tone_curve(ToneCurve curve, double v);

}  // namespace sl
