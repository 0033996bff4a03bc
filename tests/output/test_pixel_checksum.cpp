// The checksum every EXR frame carries for --resume: pinned to values computed by a separate
// implementation (Python), sensitive to every bit, and frames written with the older byte-wise
// checksum are still verified with it.
#include "stages/output/exr_frame_check.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "foundation/errors.h"
#include "stages/output/exr_io.h"
#include "tests/common/temp_dir.h"

namespace sl {
namespace {

// 37 floats = four 32-byte words of every lane and 20 bytes of tail.
std::vector<float> quarters() {
    std::vector<float> v(37);
    for (size_t i = 0; i < v.size(); ++i) v[i] = 0.25f * static_cast<float>(i);
    return v;
}

TEST(PixelChecksum, MatchesAnIndependentImplementation) {
    const std::vector<float> v = quarters();
    // python3, from foundation/checksum64.h's lanes and finaliser written out by hand.
    EXPECT_EQ(pixel_checksum(v.data(), v.size()), "f4e234e4aab5a8be");
    EXPECT_EQ(pixel_checksum(nullptr, 0), "9090306c6e91ed59");
    EXPECT_EQ(pixel_checksum_bytewise(v.data(), v.size()), "0ec601feac37003a");
    EXPECT_EQ(pixel_checksum_bytewise(nullptr, 0), "14650fb0739d0383");
}

TEST(PixelChecksum, EveryBitFlipChangesIt) {
    std::vector<float> v = quarters();
    const std::string base = pixel_checksum(v.data(), v.size());
    auto* bytes = reinterpret_cast<unsigned char*>(v.data());
    for (size_t i = 0; i < v.size() * sizeof(float); ++i)
        for (int bit = 0; bit < 8; ++bit) {
            bytes[i] ^= static_cast<unsigned char>(1u << bit);
            EXPECT_NE(pixel_checksum(v.data(), v.size()), base) << "byte " << i << " bit " << bit;
            bytes[i] ^= static_cast<unsigned char>(1u << bit);
        }
    // Two words swapped between lanes, and a value moved from one word to the next.
    std::swap(v[0], v[2]);
    EXPECT_NE(pixel_checksum(v.data(), v.size()), base);
}

TEST(PixelChecksum, FramesWithTheByteWiseChecksumStillVerify) {
    test::TempDir dir("checksum_old");
    const std::string path = dir.file("frame_0003.exr");
    std::vector<float> rgb(4 * 4 * 3);
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.01f * static_cast<float>(i);
    const ExrExpectation want{4, 4, "slowlight:settings", "abc", 3};
    std::map<std::string, std::string> meta{{"slowlight:settings", "abc"}, {kFrameIndexKey, "3"}};

    meta[kByteChecksumKey] = pixel_checksum_bytewise(rgb.data(), rgb.size());
    write_exr(path, 4, 4, rgb.data(), meta);
    EXPECT_EQ(read_verified_exr(path, want), rgb);

    meta[kByteChecksumKey] = pixel_checksum(rgb.data(), rgb.size());  // the other function's digits
    write_exr(path, 4, 4, rgb.data(), meta);
    EXPECT_THROW(read_verified_exr(path, want), RuntimeFailure);

    meta.erase(kByteChecksumKey);
    meta[kChecksumKey] = pixel_checksum(rgb.data(), rgb.size());
    write_exr(path, 4, 4, rgb.data(), meta);
    EXPECT_EQ(read_verified_exr(path, want), rgb);
}

}  // namespace
}  // namespace sl
