#include <gtest/gtest.h>
#include <fcntl.h>
#include <unistd.h>

extern "C" {
#include <libavformat/avformat.h>
}

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "foundation/errors.h"
#include "stages/output/video_encoder.h"
#include "tests/common/stdout_redirect.h"
#include "tests/common/temp_dir.h"
#include "tests/common/video_reader.h"

namespace {

constexpr int kFrames = 12;

// Frame k: a horizontal ramp whose level rises with k, so mean luma must rise too.
std::vector<uint8_t> frame(int w, int h, int k) {
    std::vector<uint8_t> rgb(size_t(w) * size_t(h) * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            uint8_t* p = &rgb[(size_t(y) * size_t(w) + size_t(x)) * 3];
            const int level = 20 + 15 * k + 20 * x / w;
            p[0] = uint8_t(level);
            p[1] = uint8_t(level + 5);
            p[2] = uint8_t(level / 2);
        }
    return rgb;
}

void encode(const sl::VideoSettings& vs, int frames = kFrames) {
    auto enc = sl::VideoEncoder::open(vs);
    for (int k = 0; k < frames; ++k) enc->write_frame(frame(vs.width, vs.height, k).data());
    enc->finish();
    EXPECT_EQ(enc->frames_written(), frames);
}

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

size_t count(const std::string& text, const std::string& word) {
    size_t n = 0;
    for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
    return n;
}

using sl::test::StdoutRedirect;

struct Case {
    const char* ext;
    int width, height;
    double fps;
    const char* codec;
};

class VideoRoundTrip : public ::testing::TestWithParam<Case> {};

}  // namespace

TEST_P(VideoRoundTrip, DecodesToWhatWasWritten) {
    const Case c = GetParam();
    sl::test::TempDir dir;
    const std::string path = dir.file(std::string("out") + c.ext);
    encode({.path = path, .width = c.width, .height = c.height, .fps = c.fps});
    EXPECT_EQ(dir.entries(), std::vector<std::string>{std::string("out") + c.ext});

    const sl::VideoInfo info = sl::read_video(path);
    EXPECT_EQ(info.codec, c.codec);
    EXPECT_EQ(info.frames, kFrames);
    EXPECT_EQ(info.width, c.width);
    EXPECT_EQ(info.height, c.height);
    EXPECT_NEAR(info.fps, c.fps, 1e-3);
    ASSERT_EQ(info.mean_luma.size(), size_t(kFrames));
    for (int k = 1; k < kFrames; ++k)
        EXPECT_GE(info.mean_luma[size_t(k)], info.mean_luma[size_t(k - 1)]) << "frame " << k;
    EXPECT_GT(info.mean_luma.back(), info.mean_luma.front() + 100);
}

INSTANTIATE_TEST_SUITE_P(
    Containers, VideoRoundTrip,
    ::testing::Values(Case{".mp4", 64, 48, 24, "h264"}, Case{".mp4", 65, 37, 29.97, "h264"},
                      Case{".mov", 64, 48, 30, "h264"}, Case{".mkv", 64, 48, 24, "ffv1"},
                      Case{".mkv", 65, 37, 29.97, "ffv1"}, Case{".webm", 64, 48, 24, "vp9"},
                      Case{".webm", 65, 37, 29.97, "vp9"}),
    [](const auto& info) {
        return std::string(info.param.ext + 1) + "_" + std::to_string(info.param.width) + "x" +
               std::to_string(info.param.height);
    });

TEST(VideoEncoder, TagsBt709LimitedRange) {
    sl::test::TempDir dir;
    const std::string path = dir.file("tagged.mp4");
    encode({.path = path, .width = 64, .height = 48}, 2);

    AVFormatContext* fmt = nullptr;
    ASSERT_EQ(avformat_open_input(&fmt, path.c_str(), nullptr, nullptr), 0);
    ASSERT_GE(avformat_find_stream_info(fmt, nullptr), 0);
    const AVCodecParameters* par = fmt->streams[0]->codecpar;
    EXPECT_EQ(par->color_primaries, AVCOL_PRI_BT709);
    EXPECT_EQ(par->color_trc, AVCOL_TRC_BT709);
    EXPECT_EQ(par->color_space, AVCOL_SPC_BT709);
    EXPECT_EQ(par->color_range, AVCOL_RANGE_MPEG);
    avformat_close_input(&fmt);
}

TEST(VideoEncoder, ConvertsWithBt709Coefficients) {
    // Uncompressed y4m, so the stored Y is exactly swscale's: pure red is 16 + 219 * 0.2126 = 63
    // with BT.709 (BT.601 would give 82).
    sl::test::TempDir dir;
    const std::string path = dir.file("red.y4m");
    std::FILE* file = std::fopen(path.c_str(), "wb");
    ASSERT_TRUE(file);
    const std::vector<uint8_t> red = {255, 0, 0, 255, 0, 0, 255, 0, 0, 255, 0, 0};
    {
        StdoutRedirect redirect(::fileno(file));
        auto enc = sl::VideoEncoder::open({.path = "-", .width = 2, .height = 2});
        enc->write_frame(red.data());
        enc->finish();
    }
    std::fclose(file);
    const std::string y4m = slurp(path);
    const size_t at = y4m.find("FRAME\n");
    ASSERT_NE(at, std::string::npos);
    EXPECT_NEAR(uint8_t(y4m[at + 6]), 63, 1);
}

TEST(VideoEncoder, StdoutCarriesYuv4mpeg) {
    sl::test::TempDir dir;
    const std::string path = dir.file("stdout.y4m");
    std::FILE* file = std::fopen(path.c_str(), "wb");
    ASSERT_TRUE(file);
    bool stdout_still_open = false;
    {
        StdoutRedirect redirect(::fileno(file));
        encode({.path = "-", .width = 64, .height = 48, .fps = 24});
        stdout_still_open = ::fcntl(1, F_GETFD) != -1;  // closing the encoder keeps fd 1
    }
    std::fclose(file);
    EXPECT_TRUE(stdout_still_open);
    const std::string y4m = slurp(path);
    EXPECT_EQ(y4m.rfind("YUV4MPEG2 W64 H48 F24:1 ", 0), 0u) << y4m.substr(0, 80);
    EXPECT_EQ(count(y4m, "FRAME"), size_t(kFrames));
    EXPECT_EQ(y4m.size(), y4m.find('\n') + 1 + kFrames * (6 + 64 * 48 * 3 / 2));  // 4:2:0

    const sl::VideoInfo info = sl::read_video(path);  // and a decoder agrees
    EXPECT_EQ(info.frames, kFrames);
    EXPECT_EQ(info.width, 64);
    EXPECT_EQ(info.height, 48);
}

TEST(VideoEncoder, StdoutOddSizeUses444) {
    sl::test::TempDir dir;
    const std::string path = dir.file("odd.y4m");
    std::FILE* file = std::fopen(path.c_str(), "wb");
    ASSERT_TRUE(file);
    {
        StdoutRedirect redirect(::fileno(file));
        encode({.path = "-", .width = 65, .height = 37, .fps = 29.97}, 3);
    }
    std::fclose(file);
    const std::string y4m = slurp(path);
    EXPECT_EQ(y4m.rfind("YUV4MPEG2 W65 H37 F2997:100 ", 0), 0u) << y4m.substr(0, 80);
    EXPECT_NE(y4m.substr(0, y4m.find('\n')).find("C444"), std::string::npos);
    EXPECT_EQ(count(y4m, "FRAME"), 3u);
}

// convert() and send() are write_frame() in two steps, with two staging frames so that the
// next frame can be converted before the last one is sent: the same frames must come out.
TEST(VideoEncoder, ConvertingAheadWritesWhatWriteFrameWrites) {
    sl::test::TempDir dir;
    const sl::VideoSettings one{.path = dir.file("one.mkv"), .width = 64, .height = 48};
    encode(one);
    sl::VideoSettings two = one;
    two.path = dir.file("two.mkv");
    {
        auto enc = sl::VideoEncoder::open(two);
        for (int k = 0; k < kFrames; ++k) {
            enc->convert(frame(two.width, two.height, k).data(), k % 2);
            if (k > 0) enc->send((k - 1) % 2);  // frame k is already converted, in the other slot
        }
        enc->send((kFrames - 1) % 2);
        enc->finish();
        EXPECT_EQ(enc->frames_written(), kFrames);
    }
    const sl::VideoInfo a = sl::read_video(one.path), b = sl::read_video(two.path);
    ASSERT_EQ(b.frames, kFrames);
    EXPECT_EQ(a.mean_luma, b.mean_luma);  // FFV1 is lossless: equal frames, equal means
    for (int k = 1; k < kFrames; ++k) EXPECT_GT(b.mean_luma[size_t(k)], b.mean_luma[size_t(k - 1)]);
}

TEST(VideoEncoder, ClosedPipeIsRuntimeFailure) {
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    ::close(fds[0]);  // nobody will read: every write fails with EPIPE
    bool failed = false;
    {
        StdoutRedirect redirect(fds[1]);
        try {
            encode({.path = "-", .width = 64, .height = 48});
        } catch (const sl::RuntimeFailure&) {
            failed = true;
        }
    }
    ::close(fds[1]);
    EXPECT_TRUE(failed);  // and we are still alive: SIGPIPE did not kill the process
}

TEST(VideoEncoder, UnknownExtensionIsInputError) {
    sl::test::TempDir dir;
    const std::string path = dir.file("out.xyz");
    try {
        sl::VideoEncoder::open({.path = path, .width = 64, .height = 48});
        FAIL() << "expected InputError";
    } catch (const sl::InputError& e) {
        EXPECT_EQ(std::string(e.what()), "-o " + path +
                                             ": unknown video container '.xyz' (use .mp4, .mov, "
                                             ".mkv, .webm, - for stdout, or a device or FIFO)");
    }
    EXPECT_TRUE(dir.entries().empty());
}

TEST(VideoEncoder, BadSettingsAreInputErrors) {
    sl::test::TempDir dir;
    const std::string path = dir.file("out.mp4");
    EXPECT_THROW(sl::VideoEncoder::open({.path = path, .width = 0, .height = 48}), sl::InputError);
    EXPECT_THROW(sl::VideoEncoder::open({.path = path, .width = 64, .height = 48, .fps = 0}),
                 sl::InputError);
    EXPECT_THROW(sl::VideoEncoder::open({.path = path, .width = 64, .height = 48, .quality = 52}),
                 sl::InputError);
    EXPECT_THROW(sl::VideoEncoder::open({.path = dir.file("noext"), .width = 64, .height = 48}),
                 sl::InputError);
    EXPECT_TRUE(dir.entries().empty());
}

TEST(VideoEncoder, UnwritablePathFailsInOpen) {
    sl::test::TempDir dir;
    std::filesystem::create_directory(dir.file("sub.mkv"));
    for (const std::string& path : {dir.file("missing/out.mp4"), dir.file("sub.mkv")}) {
        try {
            sl::VideoEncoder::open({.path = path, .width = 64, .height = 48});
            ADD_FAILURE() << "expected RuntimeFailure for " << path;
        } catch (const sl::RuntimeFailure& e) {
            EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"sub.mkv"});  // nothing left behind
}

TEST(VideoEncoder, AppearsOnlyWhenFinished) {
    sl::test::TempDir dir;
    const std::string path = dir.file("out.mkv");
    auto enc = sl::VideoEncoder::open({.path = path, .width = 32, .height = 16});
    enc->write_frame(frame(32, 16, 0).data());
    EXPECT_FALSE(std::filesystem::exists(path));  // still under a hidden temporary name
    enc->finish();
    enc->finish();  // idempotent
    EXPECT_TRUE(std::filesystem::exists(path));
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.mkv"});
}

TEST(VideoEncoder, DestructorDropsTheUnfinishedVideo) {
    sl::test::TempDir dir;
    const std::string path = dir.file("partial.mp4");
    {
        auto enc = sl::VideoEncoder::open({.path = path, .width = 32, .height = 16});
        for (int k = 0; k < 3; ++k) enc->write_frame(frame(32, 16, k).data());
    }  // e.g. unwinding after an error mid-render: a shortened video must not look whole
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_TRUE(dir.entries().empty());  // nor is its temporary left behind
}

TEST(VideoEncoder, LosslessMp4) {
    sl::test::TempDir dir;
    const std::string path = dir.file("lossless.mp4");
    encode({.path = path, .width = 64, .height = 48, .lossless = true}, 3);
    const sl::VideoInfo info = sl::read_video(path);
    EXPECT_EQ(info.frames, 3);
}
