#pragma once
// Sensor images computed from the transient planes as they stream past, one plane at a time
// and never the whole cube: what a continuous-wave time-of-flight camera measures per
// modulation frequency (amplitude and phase), what a gated camera integrates over a window, and
// when light first reaches each pixel. Every image is per channel (R, G, B), float.
//
// The input is the frames' bins: bin k holds the radiance of the light whose arrival time falls
// in frame k (the cube's plane k + 1; the bins sum to the steady image, with the light before
// start_ns and after end_ns). With bin centres t_k and width Δ:
//   phasor(f) = sinc(fΔ) · Σ_k bin_k · exp(−2πi f t_k),  sinc(x) = sin(πx)/(πx):
//     the exact transform of bins whose light is spread evenly within each bin;
//     amplitude = |phasor|, phase = −arg(phasor) in [0, 2π): one arrival at t gives 2πf·t.
//   gate(a, w) = Σ_k bin_k · |[t_k − Δ/2, t_k + Δ/2) ∩ [a, a + w)| / Δ.
//   first_arrival = the start time of the first bin above the threshold (ns); −inf when the
//     light before start_ns already exceeds it, +inf when nothing does.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "config/sensor_options.h"
#include "foundation/timeline.h"

namespace sl {

struct SensorImage {
    std::string file;  // its name in --exr-dir: "phasor_20MHz_amplitude.exr", "gate.exr", ...
    std::vector<float> rgb;
    std::map<std::string, std::string> metadata;  // what it is, in the EXR header
};

class SensorImages {
public:
    SensorImages(const SensorRequest& request, const Timeline& timeline, int width, int height);

    void add_before(const float* rgb);        // what arrived before start_ns
    void add_bin(int k, const float* rgb);    // frame k's bin; k = 0, 1, ... in order
    bool complete() const { return bins_ == timeline_.frames; }
    std::vector<SensorImage> images() const;  // once complete
    // The file names it will write (for the output checks, before rendering).
    static std::vector<std::string> file_names(const SensorRequest& request);

private:
    SensorRequest request_;
    Timeline timeline_;
    size_t values_;  // width * height * 3
    int bins_ = 0;
    std::vector<double> phasor_re_, phasor_im_;  // per frequency, values_ each: Σ v cos, Σ v sin
    std::vector<double> gate_;
    std::vector<float> first_;
};

}  // namespace sl
