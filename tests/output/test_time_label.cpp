// --label time: the frame's time burnt into the 8-bit frames by libavfilter's drawtext. A user
// relies on the label changing only its own corner of the picture, and on the text saying the
// frame's time in a sensible unit.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <vector>

#include "stages/output/time_label.h"
#include "tests/common/temp_dir.h"
#include "tests/pipeline/run_program.h"

namespace {

// A smooth gradient, so that any change is the label's.
std::vector<uint8_t> gradient(int w, int h) {
    std::vector<uint8_t> img(static_cast<size_t>(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) img[(static_cast<size_t>(y) * w + x) * 3 + c] = static_cast<uint8_t>((x + y + 40 * c) % 200);
    return img;
}

struct Changed {
    size_t count = 0;
    int min_x = 1 << 30, max_x = -1, min_y = 1 << 30, max_y = -1;
};

Changed diff(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int w, int h) {
    Changed c;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = (static_cast<size_t>(y) * w + x) * 3;
            if (a[i] == b[i] && a[i + 1] == b[i + 1] && a[i + 2] == b[i + 2]) continue;
            ++c.count;
            c.min_x = std::min(c.min_x, x), c.max_x = std::max(c.max_x, x);
            c.min_y = std::min(c.min_y, y), c.max_y = std::max(c.max_y, y);
        }
    return c;
}

std::vector<uint8_t> read_png(const std::string& path, int& w, int& h) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return {};
    w = in->spec().width;
    h = in->spec().height;
    std::vector<uint8_t> px(static_cast<size_t>(w) * h * 3);
    in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data());
    return px;
}

}  // namespace

TEST(TimeLabel, ChangesOnlyTheBottomLeftCorner) {
    const int w = 320, h = 180;
    const std::vector<uint8_t> plain = gradient(w, h);
    std::vector<uint8_t> a = plain, b = plain, a2 = plain;
    sl::TimeLabel label(w, h);
    label.burn(a.data(), sl::format_frame_time(3.5, 0.5));
    label.burn(b.data(), sl::format_frame_time(12.5, 0.5));
    label.burn(a2.data(), sl::format_frame_time(3.5, 0.5));

    Changed c = diff(plain, a, w, h);
    ASSERT_GT(c.count, 100u) << "no text drawn";
    EXPECT_LT(c.max_x, w / 2) << "the label reaches past the left half";
    EXPECT_GT(c.min_y, h * 2 / 3) << "the label reaches above the bottom third";
    EXPECT_LT(c.count, static_cast<size_t>(w * h / 10));
    EXPECT_GT(diff(a, b, w, h).count, 0u) << "two times, the same picture";
    EXPECT_EQ(diff(a, a2, w, h).count, 0u) << "the same time drawn twice differs";
}

TEST(TimeLabel, SaysTheTimeInAUnitThatSuitsTheWindow) {
    EXPECT_EQ(sl::format_frame_time(3.5, 0.5), "t = 3.5 ns");
    EXPECT_EQ(sl::format_frame_time(3.25, 0.25), "t = 3.25 ns");
    EXPECT_EQ(sl::format_frame_time(24, 1), "t = 24 ns");
    EXPECT_EQ(sl::format_frame_time(0.05, 0.01), "t = 50 ps");
    EXPECT_EQ(sl::format_frame_time(20000, 1000), "t = 20 \u00b5s");
}

// End to end: the same render with and without --label time differs only in the label's corner.
TEST(TimeLabel, LabelledFramesDifferFromPlainOnesOnlyInTheLabel) {
    sl::test::TempDir dir;
    const std::vector<std::string> common{"render", "--frames", "3", "--passes", "1", "--photons", "2000",
                                          "--width", "96", "--height", "64", "--no-progress", "--png-dir"};
    std::vector<std::string> plain = common, labelled = common;
    plain.push_back(dir.file("plain"));
    labelled.push_back(dir.file("label"));
    labelled.insert(labelled.end(), {"--label", "time"});
    ASSERT_EQ(sl::test::run_program(plain).exit_code, 0);
    sl::test::ProgramResult r = sl::test::run_program(labelled);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* f : {"frame_0000.png", "frame_0002.png"}) {
        int w = 0, h = 0, w2 = 0, h2 = 0;
        std::vector<uint8_t> a = read_png(dir.file(std::string("plain/") + f), w, h);
        std::vector<uint8_t> b = read_png(dir.file(std::string("label/") + f), w2, h2);
        ASSERT_EQ(w, 96);
        ASSERT_EQ(w2, w);
        Changed c = diff(a, b, w, h);
        EXPECT_GT(c.count, 20u) << f;
        EXPECT_LT(c.max_x, w * 3 / 4) << f;
        EXPECT_GT(c.min_y, h / 2) << f;
    }
}
