// OpenEXR's own maximum image size is set to our header walk's bound (exr_limits.h): a window
// one pixel wider than the walk allows is refused by the walk with a message naming the file,
// and by OpenEXR itself when a file is opened without the walk; the bound itself passes.
#include "stages/output/exr_limits.h"

#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "foundation/errors.h"
#include "stages/output/exr_header_scan.h"
#include "stages/output/exr_io.h"
#include "tests/common/temp_dir.h"

namespace sl {
namespace {

// An 8 x 6 frame whose windows are then forged to `width` x 6 in the file's bytes.
std::string forged_wide_frame(const test::TempDir& dir, int32_t width) {
    const std::string path = dir.file("wide.exr");
    std::vector<float> rgb(8 * 6 * 3, 0.5f);
    write_exr(path, 8, 6, rgb.data(), {});
    std::ifstream in(path, std::ios::binary);
    std::vector<char> b{std::istreambuf_iterator<char>(in), {}};
    for (std::string key : {"dataWindow", "displayWindow"}) {
        key += std::string(1, '\0') + "box2i" + std::string(1, '\0');
        auto it = std::search(b.begin(), b.end(), key.begin(), key.end());
        EXPECT_NE(it, b.end()) << key;
        const int32_t box[4] = {0, 0, width - 1, 5};
        std::memcpy(&*(it + static_cast<long>(key.size()) + 4), box, 16);  // past the attribute's size
    }
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(b.data(), static_cast<std::streamsize>(b.size()));
    return path;
}

// What OpenEXR checks of a header when it opens a file (sanityCheck), for a w x h image.
void check(long long w, long long h) {
    Imf::Header header(static_cast<int>(w), static_cast<int>(h));
    header.channels().insert("R", Imf::Channel(Imf::FLOAT));
    header.sanityCheck();
}

TEST(ExrLimits, OpenExrsOwnBoundIsTheHeaderWalks) {
    limit_openexr_sizes();
    EXPECT_NO_THROW(check(kMaxExrWidth, 1));
    EXPECT_NO_THROW(check(1, kMaxExrPixels));
    EXPECT_THROW(check(kMaxExrWidth + 1, 1), std::exception);
    EXPECT_THROW(check(1, kMaxExrPixels + 1), std::exception);
}

TEST(ExrLimits, AFileOverTheBoundIsRefusedByBoth) {
    test::TempDir dir("exr_limits");
    const std::string path = forged_wide_frame(dir, static_cast<int32_t>(kMaxExrWidth) + 1);
    // Our walk, before OpenEXR: the message the program prints after "error: ".
    try {
        read_exr(path);
        ADD_FAILURE() << "a window over the bound was read";
    } catch (const RuntimeFailure& e) {
        const std::string why = e.what();
        EXPECT_EQ(why.rfind("cannot read EXR '" + path + "'", 0), 0u) << why;
        EXPECT_NE(why.find("too large"), std::string::npos) << why;
    }
    // OpenEXR itself, opening the file without the walk: its own limit, not a later failure.
    limit_openexr_sizes();
    try {
        Imf::InputFile in(path.c_str());
        ADD_FAILURE() << "OpenEXR opened a window over the bound";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("maximum width"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace sl
