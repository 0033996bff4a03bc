#pragma once
// The sRGB byte of exposure * x for a float x, found by its bits alone. For one exposure the
// bytes split the floats into 256 runs: exposure * x (a double product, rounded, so it never
// decreases as x grows) passes each byte's lower bound at one float, found once by bisection
// over the float bits. A value's byte is then the number of those thresholds at or below it:
// a guess from its top bits, a step, an integer compare. No double arithmetic per value, and
// the byte is exactly what round(255 * oetf(min(exposure * x, 1))) gives (tone_map.h).
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

namespace sl {

class SrgbByteTable {
public:
    // For 0 < exposure < infinity (checked by the caller).
    explicit SrgbByteTable(double exposure);

    double exposure() const { return exposure_; }

    // The thresholds and guesses as plain pointers: a loop storing bytes through a uint8_t*
    // may alias anything read through `this`, and would reload them for every value.
    struct View {
        const uint32_t* at;    // at[b]: the smallest float bits whose byte is b or more; at[256] a sentinel
        const uint8_t* guess;  // by bits >> kGuessShift: the byte of the bin's first float
        bool one_step;         // no bin holds two thresholds past its first float
        // kOneStep: only when one_step (then without a loop or a branch).
        template <bool kOneStep>
        uint8_t byte(float x) const {
            uint32_t bits = std::bit_cast<uint32_t>(x);
            // Negative values (sign bit set) and NaN (above +inf) are 0, as in the formula.
            bits = bits > kInfBits ? 0u : bits;
            uint32_t b = guess[bits >> kGuessShift];
            b += bits >= at[b + 1];
            if constexpr (!kOneStep)
                while (bits >= at[b + 1]) ++b;
            return static_cast<uint8_t>(b);
        }
    };
    // A bin is 1/128 of an octave and a byte at least 1/106 of one, so one step is the rule;
    // only extreme exposures, where many bytes begin among the smallest floats, need more.
    View view() const { return {at_.data(), guess_.data(), one_step_}; }

    // For every byte b, the smallest linear value in [0, 1] that rounds to it under the sRGB
    // formula; [256] is infinity.
    static const std::array<double, 257>& lower_bounds();

    static constexpr uint32_t kInfBits = 0x7F800000u;
    static constexpr int kGuessShift = 16;

private:
    double exposure_;
    std::array<uint32_t, 257> at_{};
    std::vector<uint8_t> guess_;
    bool one_step_ = true;
};

}  // namespace sl
