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
inline constexpr const char* kChecksumKey = "slowlight:pixels_checksum64";
// The checksum frames carried before (FNV-1a, one byte at a time: ~1 ms a 256x256 frame on the
// EXR writer's thread); such frames are still verified with it on --resume.
inline constexpr const char* kByteChecksumKey = "slowlight:pixels_fnv1a64";

// foundation/checksum64.h's checksum of the float values' bytes, as 16 hex digits.
std::string pixel_checksum(const float* values, size_t count);
// The older byte-wise FNV-1a (64 bit) of the bytes, as 16 hex digits: what kByteChecksumKey holds.
std::string pixel_checksum_bytewise(const float* values, size_t count);

struct ExrExpectation {
    int width = 0, height = 0;
    std::string fingerprint_key, fingerprint;  // header key and the value it must have
    std::optional<int> frame;  // the frame index it must carry; nullopt: the steady image
};

// The file's RGB pixels (width*height*3 floats, finite and >= 0) if it is exactly what was
// expected. Throws InputError when the fingerprint differs (a frame of another render: never
// mixed in, never silently replaced), RuntimeFailure naming the file and what is wrong
// otherwise (the caller renders the frame again).
std::vector<float> read_verified_exr(const std::string& path, const ExrExpectation& expect);

}  // namespace sl
