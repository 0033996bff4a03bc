#pragma once
// Write-then-rename: outputs appear under their final name only once complete, so a crash
// or a failed write never leaves a truncated file that looks whole.
//
// Where the bytes of an output path go:
//   - a regular file, or a name that does not exist yet: a temporary sibling, renamed on commit;
//   - a symbolic link: written through to the file it points to (the link stays a link); the
//     temporary goes beside that file;
//   - a device, FIFO or socket (/dev/null, a named pipe), or a link through a process's file
//     descriptors (/dev/stdout, /proc/self/fd/N): written in place, never replaced.
// Temporaries are named `.slowlight-tmp-<pid>-<n>-<name>`: the pid tells a later run whether
// their writer is gone (remove_stale_temporaries), and the name keeps the extension.
#include <string>

namespace sl {

inline constexpr const char* kTempPrefix = ".slowlight-tmp-";

struct OutputPlace {
    std::string path;       // where to write: the link's target, or the path itself
    bool in_place = false;  // a device, FIFO or descriptor: write there directly
    bool directory = false; // the path is an existing directory (an error for a file output)
};

// Resolves symbolic links (at most 40) and says how `path` is written.
OutputPlace place_output(const std::string& path);

// Where to write `path`'s bytes now: a fresh temporary beside its (link-resolved) target, or
// `path` itself when it is written in place. Unique per process and call, so threads may write
// siblings concurrently. Temporaries are remembered until committed or discarded, so that an
// abrupt exit can remove them (remove_live_temporaries_and_exit, live_temporaries.h).
std::string temp_sibling(const std::string& path);

// Renames `temp` onto `path`'s target (nothing to do when written in place); on failure removes
// `temp` and throws RuntimeFailure naming `path`.
void commit_file(const std::string& temp, const std::string& path);

// Removes `temp` if it is one of our temporaries (never a file written in place); never throws.
void discard_file(const std::string& temp) noexcept;

// Removes temporaries in `dir` left by runs that were killed (their pid no longer exists).
// Returns how many were removed.
int remove_stale_temporaries(const std::string& dir) noexcept;

// One line: newlines in library messages would break the single `error:` line of the CLI.
std::string one_line(std::string text);

}  // namespace sl
