#pragma once
// "Did you mean ...?": the known name closest to a mistyped one (case-insensitive edit distance),
// so that `Radiance` points to `radiance` and `--frame` to `--frames`.
#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>
#include <vector>

namespace sl {

// Levenshtein distance, ignoring ASCII case.
inline size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                              std::tolower(static_cast<unsigned char>(b[j - 1]));
            const size_t next = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
            diagonal = row[j];
            row[j] = next;
        }
    }
    return row[b.size()];
}

// The closest of `known` to `name` when it is close enough to be a slip (at most a third of
// its letters off, and never more than 3); empty otherwise.
template <class Names>
std::string nearest_name(std::string_view name, const Names& known) {
    std::string best;
    size_t best_distance = std::min<size_t>(3, std::max<size_t>(1, name.size() / 3)) + 1;
    for (std::string_view k : known) {
        const size_t d = edit_distance(name, k);
        if (d < best_distance) {
            best_distance = d;
            best = std::string(k);
        }
    }
    return best;
}

}  // namespace sl
