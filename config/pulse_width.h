#pragma once
// The pulse width checked against the frame width Δ, for the scene file, the command-line
// overrides and `retime` alike (the arithmetic is the Timeline's whole-frames check).
#include <optional>
#include <string>

#include "config/scene_desc.h"

namespace sl {

// Sets e.width_frames (1 for constant emission or an omitted width). Returns what is wrong,
// as the end of an error message, or nothing when the width is fine.
std::optional<std::string> check_pulse_width(const TimeDesc& time, EmissionDesc& e);

}  // namespace sl
