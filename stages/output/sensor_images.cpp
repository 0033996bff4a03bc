#include "stages/output/sensor_images.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "foundation/constants.h"

namespace sl {
namespace {

std::string exact(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

double sinc(double x) { return x == 0 ? 1.0 : std::sin(kPiDouble * x) / (kPiDouble * x); }

}  // namespace

SensorImages::SensorImages(const SensorRequest& request, const Timeline& timeline, int width, int height)
    : request_(request), timeline_(timeline), values_(static_cast<size_t>(width) * height * 3) {
    phasor_re_.assign(request.phasor_hz.size() * values_, 0.0);
    phasor_im_.assign(request.phasor_hz.size() * values_, 0.0);
    if (request.gate_start_ns) gate_.assign(values_, 0.0);
    if (request.first_arrival) first_.assign(values_, std::numeric_limits<float>::infinity());
}

std::vector<std::string> SensorImages::file_names(const SensorRequest& request) {
    std::vector<std::string> names;
    for (double f : request.phasor_hz) {
        names.push_back("phasor_" + frequency_label(f) + "_amplitude.exr");
        names.push_back("phasor_" + frequency_label(f) + "_phase.exr");
    }
    if (request.gate_start_ns) names.push_back("gate.exr");
    if (request.first_arrival) names.push_back("first_arrival.exr");
    return names;
}

void SensorImages::add_before(const float* rgb) {
    const float threshold = static_cast<float>(request_.first_arrival_threshold);
    for (size_t i = 0; i < first_.size(); ++i)
        if (rgb[i] > threshold) first_[i] = -std::numeric_limits<float>::infinity();
}

void SensorImages::add_bin(int k, const float* rgb) {
    ++bins_;
    const double lo = timeline_.edge(k), hi = timeline_.edge(k + 1), centre_ns = 0.5 * (lo + hi);
    // Per frequency, the bin's turn: the angle in turns, reduced before it is multiplied by 2π
    // (f·t may be many turns).
    const size_t nf = request_.phasor_hz.size();
    std::vector<double> c(nf), s(nf);
    for (size_t n = 0; n < nf; ++n) {
        const double turns = request_.phasor_hz[n] * centre_ns * 1e-9;
        const double angle = 2 * kPiDouble * (turns - std::floor(turns));
        c[n] = std::cos(angle);
        s[n] = std::sin(angle);
    }
    double overlap = 0;
    if (!gate_.empty()) {
        const double a = *request_.gate_start_ns, b = a + *request_.gate_width_ns;
        overlap = std::max(0.0, std::min(hi, b) - std::max(lo, a)) / (hi - lo);
    }
    const float threshold = static_cast<float>(request_.first_arrival_threshold);
    const float start = static_cast<float>(lo);
    // Every value is its own sum, made in bin order whatever the split: the same bits for any
    // thread count (and on MPI rank 0, which gets whole planes).
    tbb::parallel_for(tbb::blocked_range<size_t>(0, values_, 8192), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t n = 0; n < nf; ++n) {
            double* re = phasor_re_.data() + n * values_;
            double* im = phasor_im_.data() + n * values_;
            for (size_t i = r.begin(); i < r.end(); ++i) {
                re[i] += rgb[i] * c[n];
                im[i] += rgb[i] * s[n];
            }
        }
        if (overlap > 0)
            for (size_t i = r.begin(); i < r.end(); ++i) gate_[i] += rgb[i] * overlap;
        if (!first_.empty())
            for (size_t i = r.begin(); i < r.end(); ++i)
                if (rgb[i] > threshold && first_[i] == std::numeric_limits<float>::infinity()) first_[i] = start;
    });
}

std::vector<SensorImage> SensorImages::images() const {
    std::vector<SensorImage> out;
    const double delta = timeline_.delta();
    for (size_t n = 0; n < request_.phasor_hz.size(); ++n) {
        const double f = request_.phasor_hz[n], correction = sinc(f * delta * 1e-9);
        SensorImage amp, phase;
        amp.file = "phasor_" + frequency_label(f) + "_amplitude.exr";
        phase.file = "phasor_" + frequency_label(f) + "_phase.exr";
        amp.rgb.resize(values_);
        phase.rgb.resize(values_);
        const double* re = phasor_re_.data() + n * values_;
        const double* im = phasor_im_.data() + n * values_;
        for (size_t i = 0; i < values_; ++i) {
            amp.rgb[i] = static_cast<float>(correction * std::hypot(re[i], im[i]));
            // Σ v e^{−iθ} = re − i·im: its phase lag is atan2(im, re), wrapped into [0, 2π).
            double p = std::atan2(im[i], re[i]);
            if (p < 0) p += 2 * kPiDouble;
            phase.rgb[i] = static_cast<float>(p);
        }
        const std::map<std::string, std::string> common = {
            {"slowlight:sensor", "phasor"},
            {"slowlight:frequency_hz", exact(f)},
            {"slowlight:sinc_correction", exact(correction)},
            {"slowlight:window_ns", exact(timeline_.start_ns) + " " + exact(timeline_.end_ns)}};
        amp.metadata = phase.metadata = common;
        amp.metadata["slowlight:units"] = "radiance W sr^-1 m^-2: sinc(f*delta) * |sum_k bin_k exp(-2 pi i f t_k)|";
        phase.metadata["slowlight:units"] = "radians in [0, 2 pi): one arrival at t ns gives 2 pi f t";
        out.push_back(std::move(amp));
        out.push_back(std::move(phase));
    }
    if (!gate_.empty()) {
        SensorImage g;
        g.file = "gate.exr";
        g.rgb.assign(gate_.begin(), gate_.end());
        g.metadata = {{"slowlight:sensor", "gate"},
                      {"slowlight:gate_start_ns", exact(*request_.gate_start_ns)},
                      {"slowlight:gate_width_ns", exact(*request_.gate_width_ns)},
                      {"slowlight:units", "radiance W sr^-1 m^-2 of the light arriving within the gate"}};
        out.push_back(std::move(g));
    }
    if (!first_.empty()) {
        SensorImage f;
        f.file = "first_arrival.exr";
        f.rgb = first_;
        f.metadata = {{"slowlight:sensor", "first_arrival"},
                      {"slowlight:threshold", exact(request_.first_arrival_threshold)},
                      {"slowlight:units", "ns: the start of the first frame whose bin exceeds the threshold; "
                                          "-inf: before start_ns, +inf: never"}};
        out.push_back(std::move(f));
    }
    return out;
}

}  // namespace sl
