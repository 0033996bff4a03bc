#pragma once
// Durations on the command line (--time-limit, --checkpoint-every): a number followed by a
// unit, s, m or h, several parts allowed ("90s", "20m", "2h", "1h30m", "0.5s", "250ms"); a bare
// number is seconds.
#include <optional>
#include <string>
#include <string_view>

namespace sl {

// Seconds, or nothing when malformed, negative or not finite.
std::optional<double> parse_duration(std::string_view text);

// "1h02m", "3m05s", "12.5s": for messages.
std::string format_duration(double seconds);

}  // namespace sl
