// --tone linear|filmic|log: each curve starts at black, rises monotonically, reaches white where
// its formula says, and the bytes written are the sRGB encoding of the curve's value.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "stages/output/tone_map.h"

using sl::ToneCurve;

namespace {
double srgb(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055; }
}  // namespace

TEST(ToneCurves, StartAtBlackRiseAndReachWhiteWhereStated) {
    for (ToneCurve c : {ToneCurve::Linear, ToneCurve::Filmic, ToneCurve::Log}) {
        EXPECT_EQ(sl::tone_curve(c, 0), 0.0);
        EXPECT_EQ(sl::tone_curve(c, -1), 0.0);
        EXPECT_EQ(sl::tone_curve(c, std::nan("")), 0.0);
        double last = 0;
        for (double v = 0.001; v < 100; v *= 1.1) {
            const double y = sl::tone_curve(c, v);
            EXPECT_GE(y, last) << v;
            EXPECT_LE(y, 1.0);
            last = y;
        }
    }
    EXPECT_DOUBLE_EQ(sl::tone_curve(ToneCurve::Linear, 0.5), 0.5);
    EXPECT_EQ(sl::tone_curve(ToneCurve::Linear, 1.5), 1.0);
    // Log: white at 4, and the darks lifted: a hundredth of white shows as about 0.037.
    EXPECT_NEAR(sl::tone_curve(ToneCurve::Log, 4), 1.0, 1e-12);
    EXPECT_NEAR(sl::tone_curve(ToneCurve::Log, 0.01), std::log1p(0.16) / std::log1p(64.0), 1e-12);
    EXPECT_GT(sl::tone_curve(ToneCurve::Log, 0.01), 3 * sl::tone_curve(ToneCurve::Linear, 0.01));
    // Filmic: below white at 1 (a shoulder), white from about 7.24 on (the root of the fit).
    EXPECT_NEAR(sl::tone_curve(ToneCurve::Filmic, 1), 2.54 / 3.16, 1e-12);
    EXPECT_LT(sl::tone_curve(ToneCurve::Filmic, 7.0), 1.0);
    EXPECT_EQ(sl::tone_curve(ToneCurve::Filmic, 7.3), 1.0);
}

TEST(ToneCurves, BytesAreTheSrgbEncodingOfTheCurve) {
    const int w = 64, h = 1;
    std::vector<float> rgb(w * 3);
    for (int i = 0; i < w * 3; ++i) rgb[i] = 0.0005f * std::pow(1.12f, static_cast<float>(i));
    for (ToneCurve c : {ToneCurve::Linear, ToneCurve::Filmic, ToneCurve::Log}) {
        std::vector<uint8_t> out(w * 3);
        sl::tone_map_srgb8(rgb.data(), w, h, 2.0, out.data(), c);
        for (int i = 0; i < w * 3; ++i) {
            const double expect = 255 * srgb(sl::tone_curve(c, 2.0 * static_cast<double>(rgb[i])));
            EXPECT_NEAR(out[i], expect, 0.51) << "value " << i;
        }
    }
}
