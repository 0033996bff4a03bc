#include "config/sensor_options.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "config/text_util.h"

namespace sl {
namespace {

std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

// A number followed by an optional unit from `units` (lower case, with its factor).
template <size_t N>
std::optional<double> number_with_unit(std::string_view text, const std::pair<const char*, double> (&units)[N],
                                       bool unit_required) {
    const std::string t = lower(text);
    for (const auto& [unit, factor] : units) {
        const std::string_view u(unit);
        if (t.size() > u.size() && std::string_view(t).ends_with(u)) {
            std::optional<double> v = parse_whole<double>(std::string_view(t).substr(0, t.size() - u.size()));
            if (!v) return std::nullopt;
            return *v * factor;
        }
    }
    if (unit_required) return std::nullopt;
    return parse_whole<double>(t);
}

}  // namespace

FrequencyList parse_frequencies(std::string_view text) {
    // Longest suffixes first: "mhz" must not be read as "hz" after "m".
    static const std::pair<const char*, double> kUnits[] = {{"ghz", 1e9}, {"mhz", 1e6}, {"khz", 1e3}, {"hz", 1.0}};
    FrequencyList out;
    size_t at = 0;
    while (true) {
        const size_t comma = text.find(',', at);
        const std::string_view item = text.substr(at, comma == std::string_view::npos ? std::string_view::npos : comma - at);
        std::optional<double> hz = number_with_unit(item, kUnits, true);
        if (!hz) {
            out.error = "must be frequencies with their unit, such as 20MHz or 1.5GHz,40MHz; got '" + printable(item) + "'";
            return out;
        }
        if (!std::isfinite(*hz) || !(*hz > 0) || *hz > 1e15) {
            out.error = "a modulation frequency must be > 0 Hz and at most 1e15 Hz, got '" + printable(item) + "'";
            return out;
        }
        for (double f : out.hz)
            if (frequency_label(f) == frequency_label(*hz)) {
                out.error = "frequency '" + printable(item) + "' is given twice";
                return out;
            }
        out.hz.push_back(*hz);
        if (out.hz.size() > 64) {
            out.error = "at most 64 frequencies";
            return out;
        }
        if (comma == std::string_view::npos) break;
        at = comma + 1;
    }
    return out;
}

GateWindow parse_gate(std::string_view text) {
    static const std::pair<const char*, double> kUnits[] = {{"ns", 1.0}, {"ps", 1e-3}};
    GateWindow g;
    const size_t colon = text.find(':');
    std::optional<double> start, width;
    if (colon != std::string_view::npos) {
        start = number_with_unit(text.substr(0, colon), kUnits, false);
        width = number_with_unit(text.substr(colon + 1), kUnits, false);
    }
    if (!start || !width || !std::isfinite(*start) || !std::isfinite(*width)) {
        g.error = "must be START:WIDTH in nanoseconds, such as 12:3 or 12ns:500ps; got '" + printable(text) + "'";
        return g;
    }
    if (!(*width > 0)) {
        g.error = "the gate's width must be > 0, got '" + printable(text.substr(colon + 1)) + "'";
        return g;
    }
    g.start_ns = *start;
    g.width_ns = *width;
    return g;
}

std::string frequency_label(double hz) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.9gMHz", hz / 1e6);
    return buf;
}

}  // namespace sl
