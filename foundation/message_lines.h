#pragma once
// What a user reads on stderr: one line per message, never longer than kMaxMessageLine
// characters (a file name or an error text from a model can be a megabyte), and a warning
// repeated by a file (one per triangle, per primitive) printed once, with its count.
#include <cstddef>
#include <string>
#include <unordered_map>
#include <vector>

namespace sl {

inline constexpr size_t kMaxMessageLine = 300;  // "error: " or "warning: " included

// `text` on one line (control characters become spaces), cut to `max` characters with a note of
// how much was left out.
inline std::string one_line(std::string text, size_t max) {
    for (char& c : text)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
    if (text.size() <= max) return text;
    std::string note = "... (" + std::to_string(text.size()) + " characters in all)";
    size_t keep = max > note.size() ? max - note.size() : 0;
    // Not inside a UTF-8 sequence: back up to the start of a character.
    while (keep > 0 && (static_cast<unsigned char>(text[keep]) & 0xC0) == 0x80) --keep;
    return text.substr(0, keep) + note.substr(0, max - keep);
}

// The line a message is printed as: prefix + text, at most kMaxMessageLine characters.
inline std::string message_line(const char* prefix, const std::string& text) {
    const std::string p(prefix);
    return p + one_line(text, kMaxMessageLine > p.size() ? kMaxMessageLine - p.size() : 0);
}

// Each distinct line once, in the order first seen, those seen more than once with their count.
inline std::vector<std::string> counted_lines(const std::vector<std::string>& lines) {
    std::vector<std::string> order;
    std::unordered_map<std::string, size_t> count;
    for (const std::string& l : lines)
        if (count[l]++ == 0) order.push_back(l);
    for (std::string& l : order)
        if (const size_t n = count[l]; n > 1) l += " (" + std::to_string(n) + " times)";
    return order;
}

}  // namespace sl
