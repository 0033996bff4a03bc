#pragma once
// Write-then-rename: outputs appear under their final name only once complete, so a crash
// or a failed write never leaves a truncated file that looks whole.
#include <string>

namespace sl {

// A fresh hidden name in the same directory as `path` (same filesystem, so rename is atomic).
// Unique per process and call, so threads may write siblings concurrently.
std::string temp_sibling(const std::string& path);

// Renames `temp` to `path`; on failure removes `temp` and throws RuntimeFailure naming `path`.
void commit_file(const std::string& temp, const std::string& path);

// Removes `temp` if it exists; never throws.
void discard_file(const std::string& temp) noexcept;

// One line: newlines in library messages would break the single `error:` line of the CLI.
std::string one_line(std::string text);

}  // namespace sl
