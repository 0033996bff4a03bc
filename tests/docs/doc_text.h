#pragma once
// Reading the docs the way the docs tests need them: whole files, Markdown table cells, and the
// `backticked` words of a cell.
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/test_paths.h"

namespace sl::test {

inline std::string source_path(const std::string& relative) {
    return std::string(source_dir()) + "/" + relative;
}

// The whole file, or "" when it cannot be read (the caller's expectation then fails).
inline std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

inline std::string trim(const std::string& s) {
    size_t b = s.find_first_not_of(" \t\r"), e = s.find_last_not_of(" \t\r");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

inline bool is_table_row(const std::string& line) { return trim(line).rfind("|", 0) == 0; }

// The cells of a table row "| a | b |", trimmed (a `|` inside backticks splits too: the docs
// keep none there).
inline std::vector<std::string> table_cells(const std::string& line) {
    std::string t = trim(line);
    if (!t.empty() && t.front() == '|') t.erase(0, 1);
    if (!t.empty() && t.back() == '|') t.pop_back();
    std::vector<std::string> cells;
    std::string cell;
    std::istringstream in(t);
    while (std::getline(in, cell, '|')) cells.push_back(trim(cell));
    return cells;
}

inline bool is_separator_row(const std::string& line) {
    for (const std::string& c : table_cells(line))
        if (c.find_first_not_of("-: ") != std::string::npos) return false;
    return true;
}

// The words written `like this` in a piece of text.
inline std::vector<std::string> backticked(const std::string& text) {
    std::vector<std::string> words;
    for (size_t b = text.find('`'); b != std::string::npos; b = text.find('`', b)) {
        size_t e = text.find('`', b + 1);
        if (e == std::string::npos) break;
        words.push_back(text.substr(b + 1, e - b - 1));
        b = e + 1;
    }
    return words;
}

}  // namespace sl::test
