#pragma once
// What the command line asks of the transient outputs other tools read (--cube-layout, --hdf5)
// and of the sensor images computed while frames stream (--phasor, --gate, --first-arrival):
// parsed and checked here, against the scene's time window in pipeline/render_command.cpp.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sl {

// The order of the --cube file's axes: ours (planes, height, width, 3), or mitransient's
// (height, width, time, 3) over the frames' bins only.
enum class CubeLayout { Slowlight, Mitransient };

struct SensorRequest {
    std::vector<double> phasor_hz;  // --phasor: modulation frequencies in Hz, each > 0, distinct
    std::optional<double> gate_start_ns, gate_width_ns;  // --gate START:WIDTH
    bool first_arrival = false;                          // --first-arrival
    double first_arrival_threshold = 0;  // radiance (W sr^-1 m^-2) a bin must exceed
    bool any() const { return !phasor_hz.empty() || gate_start_ns || first_arrival; }
};

// "20MHz", "1.5GHz,40MHz", "500kHz", "2e7Hz": a comma-separated list of frequencies, each with
// its unit (Hz, kHz, MHz, GHz; any case). Returns Hz, or what is wrong (the end of a message).
struct FrequencyList {
    std::vector<double> hz;
    std::string error;
};
FrequencyList parse_frequencies(std::string_view text);

// "12:3" or "12ns:3ns": the gate's start and width in nanoseconds; width > 0.
struct GateWindow {
    double start_ns = 0, width_ns = 0;
    std::string error;
};
GateWindow parse_gate(std::string_view text);

// The name a frequency gives its images: "20MHz", "1500MHz", "0.5MHz" (MHz, shortest exact form).
std::string frequency_label(double hz);

}  // namespace sl
