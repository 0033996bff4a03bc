#include "stages/output/tone_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

// A gray image: every channel of pixel i holds values[i].
std::vector<float> gray(const std::vector<float>& values) {
    std::vector<float> rgb;
    for (float v : values) rgb.insert(rgb.end(), {v, v, v});
    return rgb;
}

uint8_t map_one(float r, float g, float b, double exposure) {
    const float px[3] = {r, g, b};
    uint8_t out[3];
    sl::tone_map_srgb8(px, 1, 1, exposure, out);
    return out[0];
}

}  // namespace

TEST(ToneMap, PercentileMapsToOne) {
    std::vector<float> v(100);
    for (int i = 0; i < 100; ++i) v[size_t(i)] = float(i + 1);  // luminance 1..100
    std::shuffle(v.begin(), v.end(), std::mt19937(7));
    const auto rgb = gray(v);
    const double exposure = sl::exposure_from_steady(rgb.data(), 10, 10);
    EXPECT_NEAR(exposure, 1.0 / 99.0, 1e-9);  // 99th percentile = 99
    EXPECT_EQ(map_one(99, 99, 99, exposure), 255);
    EXPECT_LT(map_one(98, 98, 98, exposure), 255);
    EXPECT_EQ(map_one(100, 100, 100, exposure), 255);  // clamped
}

TEST(ToneMap, UsesRec709Luminance) {
    const std::vector<float> rgb = {1, 0, 0};  // pure red: Y = 0.2126
    EXPECT_NEAR(sl::exposure_from_steady(rgb.data(), 1, 1), 1.0 / 0.2126, 1e-4);
}

TEST(ToneMap, IgnoresNonFinitePixels) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<float> rgb = gray(std::vector<float>(98, 2.0f));
    rgb.insert(rgb.end(), {nan, 1, 1, inf, 0, 0});
    EXPECT_NEAR(sl::exposure_from_steady(rgb.data(), 10, 10), 0.5, 1e-9);
}

TEST(ToneMap, DarkPercentileFallsBackToMax) {
    std::vector<float> v(1000, 0.0f);
    v[500] = 4.0f;  // a single lit pixel, far beyond the 99th percentile
    const auto rgb = gray(v);
    EXPECT_NEAR(sl::exposure_from_steady(rgb.data(), 100, 10), 0.25, 1e-9);
}

TEST(ToneMap, AllBlackGivesOne) {
    const auto rgb = gray(std::vector<float>(12, 0.0f));
    EXPECT_EQ(sl::exposure_from_steady(rgb.data(), 4, 3), 1.0);
}

TEST(ToneMap, SrgbCurveAndClamping) {
    EXPECT_EQ(map_one(0.5f, 0, 0, 1.0), 188);   // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354
    EXPECT_EQ(map_one(0.25f, 0, 0, 2.0), 188);  // exposure multiplies first
    EXPECT_EQ(map_one(0.0f, 0, 0, 1.0), 0);
    EXPECT_EQ(map_one(1.0f, 0, 0, 1.0), 255);
    EXPECT_EQ(map_one(0.001f, 0, 0, 1.0), 3);   // linear toe: 12.92 * 0.001 * 255 = 3.3
    EXPECT_EQ(map_one(-1.0f, 0, 0, 1.0), 0);
    EXPECT_EQ(map_one(std::numeric_limits<float>::infinity(), 0, 0, 1.0), 255);
}

TEST(ToneMap, NanBecomesZero) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float px[6] = {nan, 0.5f, nan, 1, 1, 1};
    uint8_t out[6];
    sl::tone_map_srgb8(px, 2, 1, 1.0, out);
    EXPECT_EQ(out[0], 0);
    EXPECT_EQ(out[1], 188);
    EXPECT_EQ(out[2], 0);
    EXPECT_EQ(out[3], 255);
}

// The fast path (a table guess from the float's bits, then exact boundaries) gives the byte
// of the IEC 61966-2-1 formula itself: checked on a log-uniform spread of values over every
// byte, and right at and around each of the 255 byte boundaries.
TEST(ToneMap, EveryByteIsTheFormulasOwn) {
    auto formula = [](double c) {
        c = std::clamp(c, 0.0, 1.0);
        double v = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
        return static_cast<int>(std::lround(255.0 * v));
    };
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> log10c(-8.0, 0.2);
    std::vector<float> values;
    for (int i = 0; i < 300000; ++i) values.push_back(static_cast<float>(std::pow(10.0, log10c(rng))));
    // Each boundary: bisect (in float) for the first value whose byte changes, and its neighbours.
    for (int b = 1; b < 256; ++b) {
        float lo = 0, hi = 1;
        for (int it = 0; it < 64; ++it) {
            float mid = 0.5f * (lo + hi);
            (formula(mid) >= b ? hi : lo) = mid;
        }
        for (float v : {hi, std::nextafter(hi, 0.0f), std::nextafter(hi, 2.0f), lo}) values.push_back(v);
    }
    std::vector<float> rgb = gray(values);
    std::vector<uint8_t> out(rgb.size());
    sl::tone_map_srgb8(rgb.data(), static_cast<int>(values.size()), 1, 1.0, out.data());
    int wrong = 0;
    for (size_t i = 0; i < values.size(); ++i) wrong += out[3 * i] != formula(values[i]);
    EXPECT_EQ(wrong, 0);
}
