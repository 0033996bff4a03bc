// The packed normal's rounding (core/oct_normal.h) is an inline stand-in for std::lround, which
// the photon pass called once per coordinate of every record. Photon records must stay the same
// bit for bit, so it has to agree with lround on every value it can meet: checked on each
// integer and half-integer of its range and the floats right next to them, where rounding
// decides, and on random values in between.
#include <gtest/gtest.h>

#include <cmath>

#include "core/oct_normal.h"
#include "core/rng.h"

namespace sl {
namespace {

TEST(OctNormalRounding, AgreesWithLroundAtEveryHalfAndIntegerOfItsRange) {
    using oct_detail::round_half_away;
    long checked = 0, mismatches = 0;
    auto check = [&](float v) {
        ++checked;
        if (round_half_away(v) != std::lround(v)) {
            if (++mismatches < 5) ADD_FAILURE() << "v = " << v << ": " << round_half_away(v) << " vs " << std::lround(v);
        }
    };
    for (int k = -32767; k <= 32767; ++k) {
        for (float c : {static_cast<float>(k), k + 0.5f, k - 0.5f}) {
            float below = c, above = c;
            for (int step = 0; step < 3; ++step) {  // c itself and two floats either side
                check(below);
                check(above);
                below = std::nextafter(below, -1e9f);
                above = std::nextafter(above, 1e9f);
            }
        }
    }
    Rng rng(5, 1, 0);
    for (int i = 0; i < 1000000; ++i) check((2 * rng.uniform() - 1) * 32767.0f);
    EXPECT_EQ(mismatches, 0);
    EXPECT_GT(checked, 1000000);
}

TEST(OctNormalRounding, QuantizeKeepsTheEndsOfTheRange) {
    using oct_detail::quantize;
    EXPECT_EQ(quantize(1.0f), 32767);
    EXPECT_EQ(quantize(-1.0f), -32767);
    EXPECT_EQ(quantize(2.0f), 32767);  // clamped
    EXPECT_EQ(quantize(0.0f), 0);
    EXPECT_EQ(quantize(0.5f / 32767.0f), static_cast<int16_t>(std::lround(0.5f / 32767.0f * 32767.0f)));
}

}  // namespace
}  // namespace sl
