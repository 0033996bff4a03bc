// The bytes found from a value's float bits (srgb_byte_table.h) are the formula's own at any
// exposure: round(255 * oetf(min(exposure * x, 1))), the product in double, checked value by
// value against the formula written out here, at and around every byte's threshold.
#include "stages/output/srgb_byte_table.h"
#include "stages/output/tone_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

int formula(double c) {
    if (!(c > 0)) return 0;  // NaN too
    c = std::min(c, 1.0);
    const double v = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    return static_cast<int>(std::lround(255.0 * v));
}

// Values over every byte at this exposure, each byte's first float (bisected on the float's
// bits, as a user of the formula would find it) with its neighbours, and the special values.
std::vector<float> probe_values(double exposure) {
    std::vector<float> values;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> log10c(-9.0, 0.5);
    for (int i = 0; i < 100000; ++i)
        values.push_back(static_cast<float>(std::pow(10.0, log10c(rng)) / exposure));
    for (int b = 1; b < 256; ++b) {
        uint32_t lo = 0, hi = 0x7F800000u;  // formula(exposure * +inf) = 255 >= b
        while (hi - lo > 1) {
            const uint32_t mid = lo + (hi - lo) / 2;
            (formula(exposure * double(std::bit_cast<float>(mid))) >= b ? hi : lo) = mid;
        }
        for (uint32_t bits : {lo, hi, hi + 1, lo - (lo > 0 ? 1 : 0)}) values.push_back(std::bit_cast<float>(bits));
    }
    const float inf = std::numeric_limits<float>::infinity();
    for (float v : {0.0f, -0.0f, -1.0f, -inf, inf, std::numeric_limits<float>::quiet_NaN(),
                    -std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::denorm_min(),
                    std::numeric_limits<float>::min(), std::numeric_limits<float>::max()})
        values.push_back(v);
    return values;
}

int wrong_bytes(double exposure, sl::ToneCurve curve) {
    const std::vector<float> values = probe_values(exposure);
    std::vector<uint8_t> out(values.size());
    // One row of values.size() / 3 pixels (the channels do not interact), the rest one by one.
    const size_t whole = values.size() / 3 * 3;
    sl::tone_map_srgb8(values.data(), static_cast<int>(whole / 3), 1, exposure, out.data(), curve);
    for (size_t i = whole; i < values.size(); i += 3) {
        float px[3] = {values[i], i + 1 < values.size() ? values[i + 1] : 0.0f, i + 2 < values.size() ? values[i + 2] : 0.0f};
        uint8_t o[3];
        sl::tone_map_srgb8(px, 1, 1, exposure, o, curve);
        for (size_t k = 0; k < 3 && i + k < values.size(); ++k) out[i + k] = o[k];
    }
    int wrong = 0;
    for (size_t i = 0; i < values.size(); ++i) {
        const double exposed = exposure * double(values[i]);
        const double c = curve == sl::ToneCurve::Linear ? exposed
                                                        : double(static_cast<float>(sl::tone_curve(curve, exposed)));
        if (out[i] != formula(c)) {
            if (wrong < 5) ADD_FAILURE() << "exposure " << exposure << " value " << values[i] << ": byte " << int(out[i]) << ", formula " << formula(c);
            ++wrong;
        }
    }
    return wrong;
}

}  // namespace

TEST(SrgbByteTable, EveryByteIsTheFormulasOwnAtAnyExposure) {
    // Both loops are exercised: one step from the guess at ordinary exposures, more at extremes.
    EXPECT_TRUE(sl::SrgbByteTable(2.942).view().one_step);
    EXPECT_TRUE(sl::SrgbByteTable(1e-3).view().one_step);
    EXPECT_FALSE(sl::SrgbByteTable(1e40).view().one_step);  // bytes among the subnormals
    // The demo's exposure, simple and awkward factors, and extremes where many thresholds meet.
    for (double exposure : {2.942, 1.0, 0.37, 1.0 / 3.0, 1e-3, 7.5e4, 1e-30, 1e30, 1e40, 3e-300})
        EXPECT_EQ(wrong_bytes(exposure, sl::ToneCurve::Linear), 0) << "exposure " << exposure;
}

TEST(SrgbByteTable, CurvesTooAndExposuresChangingFromFrameToFrame) {
    // Alternating exposures (--exposure-follow gives each frame its own) and curves.
    for (int round = 0; round < 2; ++round)
        for (double exposure : {0.8, 5.5}) {
            EXPECT_EQ(wrong_bytes(exposure, sl::ToneCurve::Filmic), 0);
            EXPECT_EQ(wrong_bytes(exposure, sl::ToneCurve::Log), 0);
            EXPECT_EQ(wrong_bytes(exposure, sl::ToneCurve::Linear), 0);
        }
}

TEST(SrgbByteTable, ExposuresWithoutATableStillFollowTheFormula) {
    // Zero, negative, infinite and NaN exposures take the formula's own search.
    const float px[6] = {-0.5f, 0.5f, 0.0f, 2.0f, -2.0f, 1e-3f};
    for (double exposure : {0.0, -1.0, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
        uint8_t out[6];
        sl::tone_map_srgb8(px, 2, 1, exposure, out);
        for (int i = 0; i < 6; ++i) EXPECT_EQ(out[i], formula(exposure * double(px[i]))) << exposure << " " << px[i];
    }
}
