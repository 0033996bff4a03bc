#include "stages/output/png_io.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <vector>

#include "foundation/errors.h"
#include "tests/common/temp_dir.h"

TEST(PngIo, WritesWhatOiioReadsBack) {
    sl::test::TempDir dir;
    const std::string path = dir.file("frame_0003.png");
    const int w = 7, h = 5;
    std::vector<uint8_t> rgb(size_t(w) * h * 3);
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = uint8_t(i * 37 % 256);
    sl::write_png(path, w, h, rgb.data());

    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in) << OIIO::geterror();
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.width, w);
    EXPECT_EQ(spec.height, h);
    EXPECT_EQ(spec.nchannels, 3);
    EXPECT_EQ(std::string(in->format_name()), "png");
    std::vector<uint8_t> back(rgb.size());
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, back.data()));
    EXPECT_EQ(back, rgb);  // row 0 = top, exact bytes
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"frame_0003.png"});
}

TEST(PngIo, MissingDirectoryIsRuntimeFailure) {
    sl::test::TempDir dir;
    const std::string path = dir.file("missing/frame.png");
    const uint8_t px[3] = {1, 2, 3};
    try {
        sl::write_png(path, 1, 1, px);
        FAIL() << "expected RuntimeFailure";
    } catch (const sl::RuntimeFailure& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
}
