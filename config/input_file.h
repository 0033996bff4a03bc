#pragma once
// Inputs are read only from regular files, and their size is checked before anything is read:
// a FIFO would block in open(), a link to /dev/zero or /dev/urandom would read forever, and a
// huge file would be read into memory before any limit said no. The scene file, the cubes
// retime reads, the EXR frames --resume reads and core/mesh_loader's OBJ files go through here;
// the importers in core/import/ make the same checks themselves (tinygltf opens files by name).
#include <cstdint>
#include <functional>
#include <string>

namespace sl {

struct InputFileId {
    uint64_t size = 0;
    uint64_t device = 0, inode = 0;  // identity, for telling whether an output is this input
};

// What a non-regular file is, in words: "a directory", "a FIFO", "a character device", ...
std::string file_kind_name(unsigned st_mode);

// Checks that `path` (links followed) is a regular file of at most `max_bytes`, without
// opening it. On failure throws InputError "<label>: <why>", e.g.
//   "<label>: is a FIFO, not a <kind> (only regular files are read)".
InputFileId check_input_file(const std::string& path, uint64_t max_bytes, const std::string& label,
                             const std::string& kind);

// Reads the whole file after the same checks; the open never blocks (O_NONBLOCK) and the
// descriptor is checked again (fstat), so a file swapped for a FIFO in between is refused too.
std::string read_input_file(const std::string& path, uint64_t max_bytes, const std::string& label,
                            const std::string& kind);

// The same, handing the bytes to `chunk` piece by piece (for hashing without holding them).
void read_input_chunks(const std::string& path, uint64_t max_bytes, const std::string& label,
                       const std::string& kind, const std::function<void(const char*, size_t)>& chunk);

}  // namespace sl
