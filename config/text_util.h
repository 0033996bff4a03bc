#pragma once
// Small text helpers shared by the scene and command-line parsers.
#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>

namespace sl {

// The whole of `s` as a number of type T (no spaces, no leading '+'), or nothing.
template <class T>
std::optional<T> parse_whole(std::string_view s) {
    T v{};
    const char* end = s.data() + s.size();
    auto [p, ec] = std::from_chars(s.data(), end, v);
    if (s.empty() || ec != std::errc() || p != end) return std::nullopt;
    return v;
}

// Shortest text that reads back as `v` (1, 0.5, 1e+300).
inline std::string format_number(double v) {
    char buf[32];
    auto [p, ec] = std::to_chars(buf, buf + sizeof buf, v);
    return ec == std::errc() ? std::string(buf, p) : std::string("?");
}

// `s` made safe for a one-line message: control characters escaped, long text shortened.
inline std::string printable(std::string_view s, size_t max_chars = 80) {
    std::string out;
    for (unsigned char ch : s) {
        if (out.size() >= max_chars) return out + "...";
        if (ch < 0x20 || ch == 0x7f) {
            static const char* hex = "0123456789abcdef";
            out += "\\x";
            out += hex[ch >> 4];
            out += hex[ch & 15];
        } else {
            out += static_cast<char>(ch);
        }
    }
    return out;
}

}  // namespace sl
