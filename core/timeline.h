#pragma once
// Arrival time -> time bucket. Bucket j covers [start + j*delta, start + (j+1)*delta); a time
// exactly on an edge belongs to the later bucket, and t = end belongs to no frame.
#include <cmath>
#include <cstdint>
#include <limits>

namespace sl {

struct Timeline {
    double start_ns = 0, end_ns = 1;
    int frames = 1;

    double delta() const { return (end_ns - start_ns) / frames; }
    // The frame edge: start + k * delta (k = frames gives exactly end).
    double edge(int64_t k) const {
        return k == frames ? end_ns : start_ns + static_cast<double>(k) * delta();
    }
    // The bucket of arrival time t, negative before start, >= frames at or after end.
    int64_t bucket(double t) const {
        if (!(t == t)) return std::numeric_limits<int64_t>::max();  // NaN: no frame at all
        if (t >= end_ns) return frames + static_cast<int64_t>(std::min(std::floor((t - end_ns) / delta()), 4e18));
        double x = std::floor((t - start_ns) / delta());
        if (x < -4e18) return std::numeric_limits<int64_t>::min() / 2;
        int64_t j = static_cast<int64_t>(x);
        // The division can round across an edge: settle it against the edges themselves.
        if (edge(j) > t) --j;
        else if (edge(j + 1) <= t) ++j;
        return j;
    }
};

}  // namespace sl
