#include "config/duration.h"

#include <cctype>
#include <cmath>
#include <cstdio>

#include "config/text_util.h"

namespace sl {

std::optional<double> parse_duration(std::string_view text) {
    if (text.empty()) return std::nullopt;
    if (std::optional<double> bare = parse_whole<double>(text))
        return std::isfinite(*bare) && *bare >= 0 ? bare : std::nullopt;
    double total = 0;
    size_t i = 0;
    while (i < text.size()) {
        size_t start = i;
        while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.')) ++i;
        std::optional<double> value = parse_whole<double>(text.substr(start, i - start));
        if (!value) return std::nullopt;
        size_t unit_start = i;
        while (i < text.size() && std::isalpha(static_cast<unsigned char>(text[i]))) ++i;
        std::string_view unit = text.substr(unit_start, i - unit_start);
        double scale = 0;
        if (unit == "ms") scale = 1e-3;
        else if (unit == "s") scale = 1;
        else if (unit == "m" || unit == "min") scale = 60;
        else if (unit == "h") scale = 3600;
        else return std::nullopt;
        total += *value * scale;
    }
    if (!std::isfinite(total) || total < 0) return std::nullopt;
    return total;
}

std::string format_duration(double seconds) {
    char buf[48];
    if (!(seconds >= 0) || !std::isfinite(seconds)) return "?";
    if (seconds < 60) {
        std::snprintf(buf, sizeof buf, "%.1fs", seconds);
    } else if (seconds < 3600) {
        long s = std::lround(seconds);
        std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
    } else {
        long m = std::lround(seconds / 60);
        std::snprintf(buf, sizeof buf, "%ldh%02ldm", m / 60, m % 60);
    }
    return buf;
}

}  // namespace sl
