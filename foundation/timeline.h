#pragma once
// The time axis of a render, and the only place that does arithmetic on it: the frame width Δ,
// the frame edges, the bucket of an arrival time, how many buckets one pulse spans, and the
// check that a pulse width is a whole number of frames. The scene parser, the renderer, the
// outputs (EXR headers, time labels), `retime` and `--info` all ask this struct, so that no two
// of them can disagree by a rounding.
//
// Bucket j covers [start + j*delta, start + (j+1)*delta); a time exactly on an edge belongs to
// the later bucket, and t = end belongs to no frame.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

namespace sl {

struct Timeline {
    double start_ns = 0, end_ns = 1;
    int frames = 1;
    // How many buckets one emitted pulse spans, m = pulse width / Δ (1 for constant emission
    // and for a pulse one frame wide). A frame of a pulse render sums m buckets.
    int pulse_buckets = 1;

    // Relative tolerance when checking that a width is a whole number of frames.
    static constexpr double kWholeTolerance = 1e-6;

    // Δ, the width of one frame in ns.
    double delta() const { return (end_ns - start_ns) / frames; }
    // Whether the span gives a usable Δ: end after start, and Δ finite and positive.
    bool has_valid_delta() const {
        const double d = delta();
        return end_ns > start_ns && std::isfinite(d) && d > 0;
    }
    // The frame edge: start + k * delta (k = frames gives exactly end). Frame k spans
    // [edge(k), edge(k + 1)).
    double edge(int64_t k) const { return edge_at(k, delta()); }
    // The same edge for a Δ the caller computed once (BucketFinder): the one formula for both.
    double edge_at(int64_t k, double d) const {
        return k == frames ? end_ns : start_ns + static_cast<double>(k) * d;
    }
    // An estimate j of t's bucket, off by at most one (a rounded division or multiplication),
    // settled against the edges themselves; d is delta().
    int64_t settle(int64_t j, double t, double d) const {
        if (edge_at(j, d) > t) return j - 1;
        if (edge_at(j + 1, d) <= t) return j + 1;
        return j;
    }
    // The whole-frames check: the number of frame widths in width_ns (rounded), when width_ns
    // is a whole number >= 1 of them within kWholeTolerance relative; nothing otherwise. The
    // count is a double: a huge width may exceed any int (the caller bounds it).
    std::optional<double> whole_frames(double width_ns) const {
        const double m = width_ns / delta();
        const double whole = std::round(m);
        if (!(whole >= 1) || std::abs(m - whole) > kWholeTolerance * m) return std::nullopt;
        return whole;
    }
    // The bucket of arrival time t, negative before start, >= frames at or after end.
    int64_t bucket(double t) const {
        if (!(t == t)) return std::numeric_limits<int64_t>::max();  // NaN: no frame at all
        if (t >= end_ns) return frames + static_cast<int64_t>(std::min(std::floor((t - end_ns) / delta()), 4e18));
        double x = std::floor((t - start_ns) / delta());
        if (x < -4e18) return std::numeric_limits<int64_t>::min() / 2;
        // The division can round across an edge: settle it against the edges themselves.
        return settle(static_cast<int64_t>(x), t, delta());
    }
};

// Timeline::bucket() for many arrival times in a row (the gathers ask it for every photon): Δ and
// 1/Δ are computed once, and the division becomes a multiplication. Its estimate is within one
// bucket of the division's while |(t - start) / Δ| < 2^40, and both are settled against the same
// edges, so every answer equals bucket()'s; beyond that, at or after the end and for NaN (rare
// arrivals), bucket() itself answers.
class BucketFinder {
public:
    explicit BucketFinder(const Timeline& tl) : tl_(tl), delta_(tl.delta()), inv_delta_(1.0 / delta_) {}
    int64_t operator()(double t) const {
        const double q = (t - tl_.start_ns) * inv_delta_;
        if (!(t < tl_.end_ns) || !(std::fabs(q) < 0x1p40)) return tl_.bucket(t);
        int64_t j = static_cast<int64_t>(q);  // toward zero, then down: floor(q)
        if (static_cast<double>(j) > q) --j;
        return tl_.settle(j, t, delta_);
    }

private:
    Timeline tl_;
    double delta_, inv_delta_;
};

}  // namespace sl
