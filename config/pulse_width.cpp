#include "config/pulse_width.h"

#include "config/limits.h"
#include "config/text_util.h"

namespace sl {

// Checks the pulse width against the frame width Δ (the timeline's whole-frames check) and
// sets width_frames. Returns what is wrong, or nothing when the width is fine.
std::optional<std::string> check_pulse_width(const TimeDesc& time, EmissionDesc& e) {
    e.width_frames = 1;
    if (e.mode != EmissionMode::Pulse || e.width_ns == 0) return std::nullopt;
    const Timeline timeline{time.start_ns, time.end_ns, time.frames};
    const std::optional<double> whole = timeline.whole_frames(e.width_ns);
    if (!whole)
        return "pulse width " + format_number(e.width_ns) +
               " ns is not a whole multiple of the frame width (end_ns - start_ns)/frames = " +
               format_number(timeline.delta()) + " ns";
    if (*whole > limits::kMaxPulseFrames)
        return "pulse width " + format_number(e.width_ns) + " ns is more than " +
               std::to_string(limits::kMaxPulseFrames) + " frame widths";
    e.width_frames = static_cast<int>(*whole);
    return std::nullopt;
}

}  // namespace sl
