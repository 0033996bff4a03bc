// The checksum every EXR frame carries for --resume: XXH64, pinned to published values and to
// what `xxhsum -H1` prints for the same bytes, sensitive to every bit; frames an older build
// wrote (other checksum keys) are refused as an older slowlight's, not as another render's.
#include "stages/output/exr_frame_check.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "foundation/errors.h"
#include "foundation/xxh64.h"
#include "stages/output/exr_io.h"
#include "tests/common/temp_dir.h"

namespace sl {
namespace {

// 37 floats = four 32-byte stripes and 20 bytes of tail.
std::vector<float> quarters() {
    std::vector<float> v(37);
    for (size_t i = 0; i < v.size(); ++i) v[i] = 0.25f * static_cast<float>(i);
    return v;
}

TEST(PixelChecksum, IsXxh64) {
    // XXH64's published answers (seed 0).
    EXPECT_EQ(Xxh64().value(), 0xEF46DB3751D8E999ull);
    Xxh64 abc;
    abc.update("abc", 3);
    EXPECT_EQ(abc.value(), 0x44BC2CF5AD770999ull);
    // Streamed in pieces that split stripes: the same as at once.
    const std::vector<float> v = quarters();
    Xxh64 pieces;
    auto* bytes = reinterpret_cast<const char*>(v.data());
    pieces.update(bytes, 5), pieces.update(bytes + 5, 0), pieces.update(bytes + 5, 60);
    pieces.update(bytes + 65, v.size() * sizeof(float) - 65);
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(pieces.value()));
    // `xxhsum -H1` of the 148 bytes of 0.25 * i (i = 0..36) as little-endian float32.
    EXPECT_EQ(pixel_checksum(v.data(), v.size()), "5876245eb00a992b");
    EXPECT_EQ(std::string(hex), "5876245eb00a992b");
    EXPECT_EQ(pixel_checksum(nullptr, 0), "ef46db3751d8e999");
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

TEST(PixelChecksum, FramesOfAnOlderSlowlightAreRefused) {
    test::TempDir dir("checksum_old");
    const std::string path = dir.file("frame_0003.exr");
    std::vector<float> rgb(4 * 4 * 3);
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.01f * static_cast<float>(i);
    const ExrExpectation want{4, 4, "slowlight:settings", "abc", 3};
    std::map<std::string, std::string> meta{{"slowlight:settings", "abc"}, {kFrameIndexKey, "3"}};

    meta[kChecksumKey] = pixel_checksum(rgb.data(), rgb.size());
    write_exr(path, 4, 4, rgb.data(), meta);
    EXPECT_EQ(read_verified_exr(path, want), rgb);

    meta[kChecksumKey] = "5876245eb00a992b";  // another image's digits
    write_exr(path, 4, 4, rgb.data(), meta);
    EXPECT_THROW(read_verified_exr(path, want), RuntimeFailure);

    meta.erase(kChecksumKey);
    for (const char* older : kOlderChecksumKeys)
        for (const char* fingerprint : {"abc", "an older fingerprint"}) {
            meta[older] = "0123456789abcdef";
            meta["slowlight:settings"] = fingerprint;
            write_exr(path, 4, 4, rgb.data(), meta);
            try {
                read_verified_exr(path, want);
                ADD_FAILURE() << older << " accepted";
            } catch (const InputError& e) {
                EXPECT_NE(std::string(e.what()).find("written by an older slowlight"), std::string::npos) << e.what();
                EXPECT_NE(std::string(e.what()).find(older), std::string::npos) << e.what();
            }
            meta.erase(older);
        }
}

}  // namespace
}  // namespace sl
