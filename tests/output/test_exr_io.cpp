#include "stages/output/exr_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <vector>

#include "foundation/errors.h"
#include "tests/common/temp_dir.h"

namespace {

std::vector<float> test_image(int w, int h) {
    std::vector<float> rgb(size_t(w) * size_t(h) * 3);
    for (size_t i = 0; i < rgb.size(); ++i)
        rgb[i] = float(std::pow(1.37, double(i % 41) - 20.0)) * (i % 3 == 1 ? 1.0f : 0.123456789f);
    return rgb;
}

}  // namespace

TEST(ExrIo, FloatRoundTripIsExact) {
    sl::test::TempDir dir;
    const std::string path = dir.file("frame_0000.exr");
    const int w = 7, h = 5;
    const auto rgb = test_image(w, h);
    const std::map<std::string, std::string> meta = {{"slowlight.scene_hash", "3f2a9c"},
                                                      {"slowlight.frame", "0 of 48"}};
    sl::write_exr(path, w, h, rgb.data(), meta);

    const sl::ExrImage img = sl::read_exr(path);
    EXPECT_EQ(img.width, w);
    EXPECT_EQ(img.height, h);
    EXPECT_EQ(img.rgb, rgb);  // bit-exact in float mode
    EXPECT_EQ(img.metadata.at("slowlight.scene_hash"), "3f2a9c");
    EXPECT_EQ(img.metadata.at("slowlight.frame"), "0 of 48");
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"frame_0000.exr"});  // no temp file left
}

TEST(ExrIo, HalfRoundTripIsClose) {
    sl::test::TempDir dir;
    const std::string path = dir.file("half.exr");
    const auto rgb = test_image(4, 3);
    sl::write_exr(path, 4, 3, rgb.data(), {}, /*half=*/true);
    const sl::ExrImage img = sl::read_exr(path);
    ASSERT_EQ(img.rgb.size(), rgb.size());
    for (size_t i = 0; i < rgb.size(); ++i)
        EXPECT_NEAR(img.rgb[i], rgb[i], std::abs(rgb[i]) * 1e-3 + 1e-7) << i;
}

TEST(ExrIo, OverwritesExistingFile) {
    sl::test::TempDir dir;
    const std::string path = dir.file("steady.exr");
    const std::vector<float> a(3, 1.0f), b(3, 2.0f);
    sl::write_exr(path, 1, 1, a.data());
    sl::write_exr(path, 1, 1, b.data());
    EXPECT_EQ(sl::read_exr(path).rgb, b);
}

TEST(ExrIo, MissingDirectoryIsRuntimeFailure) {
    sl::test::TempDir dir;
    const std::string path = dir.file("no/such/dir/frame.exr");
    const std::vector<float> rgb(3, 1.0f);
    try {
        sl::write_exr(path, 1, 1, rgb.data());
        FAIL() << "expected RuntimeFailure";
    } catch (const sl::RuntimeFailure& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
}

TEST(ExrIo, ReadingGarbageIsRuntimeFailure) {
    sl::test::TempDir dir;
    EXPECT_THROW(sl::read_exr(dir.file("absent.exr")), sl::RuntimeFailure);
}

TEST(ExrIo, FullDiskIsRuntimeFailure) {
    // /dev/full takes every write with "no space left": the writer must say so, on one line,
    // not report success (its bytes go out in large blocks, and at the close).
    if (access("/dev/full", W_OK) != 0) GTEST_SKIP() << "no writable /dev/full";
    for (int side : {64, 600}) {  // within one block, and several blocks
        const auto rgb = test_image(side, side);
        try {
            sl::write_exr("/dev/full", side, side, rgb.data());
            ADD_FAILURE() << "expected RuntimeFailure";
        } catch (const sl::RuntimeFailure& e) {
            EXPECT_NE(std::string(e.what()).find("/dev/full"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("space"), std::string::npos) << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        }
    }
}
