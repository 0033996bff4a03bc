#pragma once
// A section's whole convergence state on disk (a checkpoint): everything a pass reads from the
// previous ones — per-pixel radius^2 and photon count, the ambient sums, every time slot's RGB
// sums, the largest radius, the volume radius and the number of passes done. Random streams
// are a function of the seed and the pass index, so this state and the pass index are all a
// render needs to continue exactly where it stopped.
//
// The format is full-image and pixel-ordered (pixel = row * width + column, row 0 at the top),
// little-endian, independent of the thread count and of how the buffer tiles pixels in memory,
// so that any process layout (one process, or ranks owning shares of the pixels) can read or
// write any share of it:
//
//   header, 256 bytes: magic "SLCHKPT\n", format version, header size, program version,
//     settings fingerprint, section index and count, passes done and asked for, whether the
//     section is finished, width, height, slots, frames, ambient, max radius, volume radius^2,
//     payload size, payload checksum (offset 144), header checksum (offset 248)
//   radius2       f64[pixels]
//   photon_count  f64[pixels]
//   ambient       f32[pixels][3]            (only when the header says so)
//   slots         f32[pixels][slots][3]
//
// Both checksums are XXH64 (seed 0), stored little-endian: the payload's of bytes 256 to the
// end, the header's of bytes 0 to 247, so `xxhsum -H1` reproduces them (docs/checkpoints.md).
//
// Files are written to a temporary sibling, fsync'ed, renamed and the directory fsync'ed, so a
// crash (kill -9, power loss) at any moment leaves either the previous checkpoint or the new
// one, never a mix. Reading verifies everything and throws InputError on any mismatch.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "stages/render/section_buffer.h"

namespace sl {

// 3: single scattering in the medium by next-event estimation, volume photons from depth 2
// (2: every volume photon; an image summed from both would count nothing twice but its passes
// would not be those of either build); 2: XXH64 checksums (1: hand-written ones).
inline constexpr uint32_t kSectionStateFormat = 3;
inline constexpr size_t kSectionStateHeaderBytes = 256;

// Who a checkpoint belongs to; compared field by field when reading.
struct SectionStateId {
    std::string program_version;  // at most 31 characters
    std::string fingerprint;      // settings fingerprint, at most 31 characters
    int section = 0, sections = 1;
    int passes_target = 0;        // the render's --passes
    int width = 0, height = 0;
};

struct SectionStateInfo {
    SectionStateId id;
    uint32_t format = 0;
    int passes_done = 0;
    bool finished = false;  // the section reached its last pass (or its time limit)
    int slots = 0, frames = 0;
    bool ambient = false;
    uint64_t payload_bytes = 0;
};

// Writes `buffer` atomically to `path`. Returns the bytes written. Throws RuntimeFailure.
uint64_t save_section_state(const std::string& path, const SectionBuffer& buffer, const SectionStateId& id,
                            bool finished);

// The header alone, checked for magic, format and its own checksum (InputError otherwise).
SectionStateInfo read_section_state_info(const std::string& path);

// Checks that the file at `path` is a whole, uncorrupted checkpoint of `expected` with the
// given layout (header, sizes, payload checksum) without keeping its contents. InputError.
SectionStateInfo verify_section_state(const std::string& path, const SectionStateId& expected,
                                      const SectionLayout& layout, bool ambient);

// Reads the state back into a new buffer (verified as above). InputError.
std::unique_ptr<SectionBuffer> load_section_state(const std::string& path, const SectionStateId& expected,
                                                  const SectionLayout& layout, bool ambient,
                                                  SectionStateInfo* info = nullptr);


// The same file from, or into, pixels held elsewhere (ranks that each own a share of the image;
// pipeline/distributed/section_state_on_ranks.h). The payload is visited in file order, one
// array at a time (0 radius2, 1 photon_count, 2 ambient when there is one, 3 slots), in chunks
// of whole tiles: global pixels [p0, p1), section_state_pixel_bytes(array) bytes per pixel.
struct SectionStateScalars {
    size_t pixels = 0;  // of the whole image
    int slots = 0, frames = 0;
    bool ambient = false;
    int passes_done = 0;
    double max_radius = 0, volume_radius2 = 0;
};
size_t section_state_pixel_bytes(int array, int slots);
void for_each_section_state_chunk(size_t pixels, bool ambient, const std::function<void(int, size_t, size_t)>& fn);
// `fill(array, p0, p1, out)` writes the chunk's file-order bytes to `out`.
using SectionStateFill = std::function<void(int array, size_t p0, size_t p1, char* out)>;
uint64_t save_section_state_from(const std::string& path, const SectionStateId& id, const SectionStateScalars& v,
                                 bool finished, const SectionStateFill& fill);
// `take(array, p0, p1, bytes)` receives each chunk as read (the checksum is verified only after
// the last one: a caller must not trust what it took until this returns).
using SectionStateTake = std::function<void(int array, size_t p0, size_t p1, const char* bytes)>;
SectionStateInfo load_section_state_into(const std::string& path, const SectionStateId& expected,
                                         const SectionLayout& layout, bool ambient, const SectionStateTake& take,
                                         SectionStateScalars* scalars);
// A buffer's own scalars, and its pixels [p0, p1) (its own indices) in file order, or back.
SectionStateScalars section_state_scalars(const SectionBuffer& b);
void copy_section_state_chunk(const SectionBuffer& b, int array, size_t p0, size_t p1, char* out);
void take_section_state_chunk(SectionBuffer& b, int array, size_t p0, size_t p1, const char* src);

}  // namespace sl
