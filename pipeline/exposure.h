#pragma once
// The video's exposure, decided in one place before any frame is encoded, from the same
// statistic whatever produced the images (the render's own buffer, a short preview, EXR frames
// of a resumed render, or a cube being retimed):
//
//   - pixels that see an emitter directly are left out (a lamp covering 1 % of the image must
//     not decide the exposure of the other 99 %);
//   - the statistic is the mean luminance of the remaining pixels, which neither jumps with the
//     resolution nor grows with the noise of a short preview (a high percentile does both);
//   - constant emission: the steady image's mean maps to kConstantKey; pulses: the brightest
//     frame's mean maps to kPulseKey;
//   - --exposure-percentile P instead maps the P-th percentile of those pixels (for pulses, of
//     the lit pixels of every frame pooled) to white;
//   - --exposure-follow gives each frame after the brightest one its own exposure, rising as the
//     light's energy fades (a moving average over about three frames in log space, so it glides
//     instead of flickering), never below the fixed exposure nor above 256 times it.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "config/scene_desc.h"

namespace sl {

struct RenderContext;

inline constexpr double kConstantKey = 0.25;  // the steady image's mean, exposed
inline constexpr double kPulseKey = 0.25;     // the brightest pulse frame's mean, exposed
inline constexpr double kFollowFrames = 3;     // --exposure-follow: frames its moving average spans
inline constexpr double kFollowMaxGain = 256;    // how far --exposure-follow may brighten a frame

struct ExposureRule {
    std::optional<double> percentile;  // (0, 100]: that percentile to white instead of the mean
    bool follow = false;
};

// 1 for every pixel whose footprint (centre and four corners) sees an emitter directly.
std::vector<uint8_t> emitter_pixels(const RenderContext& ctx);

// The mask as runs of [first pixel, count), for the cube's side-car, and back.
std::vector<std::pair<int64_t, int64_t>> mask_runs(const std::vector<uint8_t>& mask);
std::vector<uint8_t> mask_from_runs(const std::vector<std::pair<int64_t, int64_t>>& runs, size_t pixels);

// The exposure of every frame (and of steady.png), and what it was made from.
struct ExposurePlan {
    double base = 1;                  // the video's exposure (steady.png's too)
    std::vector<double> per_frame;    // with --exposure-follow only: frame k's exposure
    double reference = 0;             // the luminance that maps to the key (or to white)
    bool black = false;               // no light at all outside the emitters: nothing to expose
    double for_frame(int k) const {
        return k >= 0 && static_cast<size_t>(k) < per_frame.size() ? per_frame[k] : base;
    }
};

// Collects the images the exposure is made from. Give it the steady image (constant emission)
// and every frame in order (pulses, or --exposure-follow); frames may be smaller than the video
// (a preview at a quarter of the resolution): only means and percentiles are kept.
class ExposureMeter {
public:
    ExposureMeter(EmissionMode mode, ExposureRule rule, std::vector<uint8_t> mask);

    bool wants_frames() const { return mode_ == EmissionMode::Pulse || rule_.follow; }
    void add_steady(const float* rgb, size_t pixels);
    void add_frame(int k, const float* rgb, size_t pixels);
    ExposurePlan decide() const;

private:
    double mean_level(const float* rgb, size_t pixels) const;
    void sample(const float* rgb, size_t pixels, bool lit_only, int salt);

    EmissionMode mode_;
    ExposureRule rule_;
    std::vector<uint8_t> mask_;
    double steady_level_ = 0;
    std::vector<double> frame_levels_;
    std::vector<float> samples_;  // luminances for --exposure-percentile
};

}  // namespace sl
