#include "pipeline/exposure.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "stages/render/render_context.h"

namespace sl {
namespace {

float luminance(const float* p) { return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]; }

// Percentile samples are strided so that a long video keeps about a million of them.
constexpr size_t kMaxSamples = size_t(1) << 20;

}  // namespace

std::vector<uint8_t> emitter_pixels(const RenderContext& ctx) {
    std::vector<uint8_t> mask(ctx.pixels(), 0);
    bool any_area_light = false;
    for (const LightDesc& l : ctx.scene.lights) any_area_light |= l.type == LightType::Quad;
    if (!any_area_light) return mask;  // point, spot and laser sources are never seen
    const Vec3 origin = ctx.camera.position();
    const float offsets[5][2] = {{0.5f, 0.5f}, {0.02f, 0.02f}, {0.98f, 0.02f}, {0.02f, 0.98f}, {0.98f, 0.98f}};
    tbb::parallel_for(0, ctx.height, [&](int y) {
        for (int x = 0; x < ctx.width; ++x) {
            for (const auto& o : offsets) {
                SurfaceHit hit;
                if (ctx.geometry.intersect(origin, ctx.camera.direction(x + o[0], y + o[1]), 0, 1e30f, hit) &&
                    hit.light >= 0) {
                    mask[static_cast<size_t>(y) * ctx.width + x] = 1;
                    break;
                }
            }
        }
    });
    return mask;
}

std::vector<std::pair<int64_t, int64_t>> mask_runs(const std::vector<uint8_t>& mask) {
    std::vector<std::pair<int64_t, int64_t>> runs;
    for (size_t i = 0; i < mask.size();) {
        if (!mask[i]) { ++i; continue; }
        size_t j = i;
        while (j < mask.size() && mask[j]) ++j;
        runs.emplace_back(static_cast<int64_t>(i), static_cast<int64_t>(j - i));
        i = j;
    }
    return runs;
}

std::vector<uint8_t> mask_from_runs(const std::vector<std::pair<int64_t, int64_t>>& runs, size_t pixels) {
    std::vector<uint8_t> mask(pixels, 0);
    for (auto [first, count] : runs)
        for (int64_t i = std::max<int64_t>(0, first); i < first + count && i < static_cast<int64_t>(pixels); ++i)
            mask[static_cast<size_t>(i)] = 1;
    return mask;
}

ExposureMeter::ExposureMeter(EmissionMode mode, ExposureRule rule, std::vector<uint8_t> mask)
    : mode_(mode), rule_(rule), mask_(std::move(mask)) {}

double ExposureMeter::mean_level(const float* rgb, size_t pixels) const {
    const bool masked = mask_.size() == pixels;
    // Serial, in pixel order: the same sum (to the bit) on any machine and thread count.
    std::pair<double, size_t> s{0.0, 0};
    for (size_t p = 0; p < pixels; ++p) {
        if (masked && mask_[p]) continue;
        const float y = luminance(rgb + 3 * p);
        if (!std::isfinite(y)) continue;
        s.first += y;
        ++s.second;
    }
    return s.second > 0 ? s.first / static_cast<double>(s.second) : 0.0;
}

void ExposureMeter::sample(const float* rgb, size_t pixels, bool lit_only, int salt) {
    const bool masked = mask_.size() == pixels;
    const size_t stride = std::max<size_t>(1, pixels * std::max<size_t>(1, frame_levels_.size() + 1) / kMaxSamples);
    for (size_t p = (static_cast<size_t>(salt) * 7919u) % stride; p < pixels; p += stride) {
        if (masked && mask_[p]) continue;
        const float y = luminance(rgb + 3 * p);
        if (!std::isfinite(y) || (lit_only && !(y > 0))) continue;
        samples_.push_back(y);
    }
}

void ExposureMeter::add_steady(const float* rgb, size_t pixels) {
    steady_level_ = mean_level(rgb, pixels);
    if (rule_.percentile && mode_ == EmissionMode::Constant) sample(rgb, pixels, false, 0);
}

void ExposureMeter::add_frame(int k, const float* rgb, size_t pixels) {
    if (static_cast<size_t>(k) >= frame_levels_.size()) frame_levels_.resize(static_cast<size_t>(k) + 1, 0.0);
    frame_levels_[static_cast<size_t>(k)] = mean_level(rgb, pixels);
    if (rule_.percentile && mode_ == EmissionMode::Pulse) sample(rgb, pixels, true, k);
}

ExposurePlan ExposureMeter::decide() const {
    ExposurePlan plan;
    double key = kConstantKey;
    if (mode_ == EmissionMode::Constant) {
        plan.reference = steady_level_;
    } else {
        key = kPulseKey;
        for (double l : frame_levels_) plan.reference = std::max(plan.reference, l);
    }
    plan.black = !(plan.reference > 0);
    if (rule_.percentile && !samples_.empty()) {
        std::vector<float> v = samples_;
        const size_t rank = static_cast<size_t>(std::ceil(*rule_.percentile / 100.0 * static_cast<double>(v.size())));
        const size_t k = std::clamp<size_t>(rank, 1, v.size()) - 1;
        std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
        if (v[k] > 0) {
            plan.reference = v[k];
            key = 1.0;
        }
    }
    plan.base = plan.reference > 0 ? key / plan.reference : 1.0;
    if (rule_.follow && !frame_levels_.empty() && plan.reference > 0) {
        // Each frame after the brightest one wants the exposure that shows it as bright as the
        // brightest; until then, the fixed one (frames before the light arrives stay dark instead
        // of flaring). The exposure follows those wishes through a moving average in log space
        // (it glides from the fixed exposure instead of stepping, and a single frame's noise moves
        // it by a third at most), so it never drops below the fixed one and trails a steady fade
        // by about two frames.
        const size_t n = frame_levels_.size();
        const size_t peak = static_cast<size_t>(std::max_element(frame_levels_.begin(), frame_levels_.end()) -
                                                frame_levels_.begin());
        const double a = 1.0 / kFollowFrames;
        double log_gain = 0;
        plan.per_frame.assign(n, plan.base);
        for (size_t k = peak + 1; k < n; ++k) {
            const double wish = std::log(std::clamp(plan.reference / std::max(frame_levels_[k], 0.0), 1.0, kFollowMaxGain));
            log_gain += a * (wish - log_gain);
            plan.per_frame[k] = plan.base * std::exp(log_gain);
        }
    }
    return plan;
}

}  // namespace sl
