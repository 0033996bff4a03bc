#pragma once
// Reading back an EXR frame this program wrote earlier (for --resume), trusting nothing in the
// file: its size, channels, data window, frame index and pixels are checked against what the
// render expects, and the pixels against a checksum recorded in the header when it was written.
// A file copied onto another frame's name, cut short, edited or forged is refused; its
// pixels are never read beyond the buffer this render allocates.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace sl {

// Header keys written with every frame.
inline constexpr const char* kFrameIndexKey = "slowlight:frame";
inline constexpr const char* kChecksumKey = "slowlight:pixels_xxh64";
// The keys of the checksums older builds wrote (a hand-written four-lane hash, and byte-wise
// FNV-1a before it): such frames are refused on --resume as an older slowlight's.
inline constexpr const char* kOlderChecksumKeys[] = {"slowlight:pixels_checksum64", "slowlight:pixels_fnv1a64"};

// XXH64 (seed 0) of the float values' bytes (RGB interleaved, little-endian), as 16 hex digits.
std::string pixel_checksum(const float* values, size_t count);

struct ExrExpectation {
    int width = 0, height = 0;
    std::string fingerprint_key, fingerprint;  // header key and the value it must have
    std::optional<int> frame;  // the frame index it must carry; nullopt: the steady image
};

// The file's RGB pixels (width*height*3 floats, finite and >= 0) if it is exactly what was
// expected. Throws InputError when the fingerprint differs (a frame of another render: never
// mixed in, never silently replaced) or an older slowlight wrote it, RuntimeFailure naming the file and what is wrong
// otherwise (the caller renders the frame again).
std::vector<float> read_verified_exr(const std::string& path, const ExrExpectation& expect);

}  // namespace sl
