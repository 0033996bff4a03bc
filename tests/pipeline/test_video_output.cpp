// The videos the program writes, decoded back with libavformat (never trusting the writer):
// frame count, size, rate, codec, and brightness that follows the linear EXR frames.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/common/video_reader.h"
#include "tests/pipeline/pipeline_helpers.h"

namespace fs = std::filesystem;
using namespace sl::test;

namespace {

// The Cornell box (closed, constant emission) with its frame rate changed, so that the test
// sees the rate come from time.fps rather than from a default of 24.
std::string cornell_with_fps(const ScratchDir& dir, const std::string& fps) {
    std::string text = read_text(sample("cornell_box.json"));
    const std::string key = "\"fps\": 24";
    size_t at = text.find(key);
    if (at == std::string::npos) throw std::runtime_error("samples/cornell_box.json: no \"fps\": 24");
    text.replace(at, key.size(), "\"fps\": " + fps);
    std::string path = dir.file("cornell_fps.json");
    std::ofstream(path) << text;
    return path;
}

struct Container {
    const char* ext;
    const char* codec;  // what the decoder must report
};

class VideoOutput : public ::testing::TestWithParam<Container> {};

}  // namespace

TEST_P(VideoOutput, DecodesToTheRenderedFrames) {
    const Container c = GetParam();
    ScratchDir dir;
    const int frames = 8, width = 64, height = 48;
    const std::string video = dir.file(std::string("out.") + c.ext), exr = dir.file("exr");
    const std::string scene = cornell_with_fps(dir, "30");
    ProgramResult r = run_program(small_render(scene, {"-o", video, "--exr-dir", exr}, frames, 4, 20000, width, height));
    SL_EXPECT_EXIT(r, 0);
    ASSERT_TRUE(fs::exists(video));

    sl::VideoInfo v = sl::read_video(video);
    EXPECT_EQ(v.codec, c.codec);
    EXPECT_EQ(v.frames, frames);
    EXPECT_EQ(v.width, width);
    EXPECT_EQ(v.height, height);
    EXPECT_NEAR(v.fps, 30.0, 1e-6);
    ASSERT_EQ(v.mean_luma.size(), static_cast<size_t>(frames));

    // Constant emission in a closed room: every frame adds light, so the decoded brightness
    // never falls (by more than one code value of codec noise).
    for (int k = 1; k < frames; ++k)
        EXPECT_GE(v.mean_luma[k], v.mean_luma[k - 1] - 1.0) << "frame " << k << " darker than frame " << k - 1;
    EXPECT_GT(v.mean_luma.back(), v.mean_luma.front() + 1.0) << "the video should brighten";

    // Frame k of the video is frame k of the EXRs: same order of brightness.
    std::vector<double> linear = frame_means(exr, frames);
    const double rho = rank_correlation(v.mean_luma, linear);
    std::string lumas;
    for (double y : v.mean_luma) lumas += std::to_string(y) + " ";
    RecordProperty("mean_luma", lumas);
    EXPECT_GT(rho, 0.9) << "decoded luma " << lumas;
}

INSTANTIATE_TEST_SUITE_P(Containers, VideoOutput,
                         ::testing::Values(Container{"mp4", "h264"}, Container{"mov", "h264"},
                                           Container{"mkv", "ffv1"}, Container{"webm", "vp9"}),
                         [](const ::testing::TestParamInfo<Container>& i) { return std::string(i.param.ext); });

// `-o -`: YUV4MPEG2 on stdout and nothing else there (the logs go to stderr).
TEST(VideoOutputStdout, Yuv4mpegOnStdoutOnly) {
    ScratchDir dir;
    const int frames = 4, width = 32, height = 32;
    const std::string out = dir.file("stdout.y4m");
    ProgramResult r = run_program(small_render("", {"-o", "-"}, frames), out);
    SL_EXPECT_EXIT(r, 0);
    const std::string data = read_text(out);

    size_t eol = data.find('\n');
    ASSERT_NE(eol, std::string::npos) << "no header line";
    const std::string header = data.substr(0, eol);
    EXPECT_EQ(header.rfind("YUV4MPEG2 ", 0), 0u) << header;
    EXPECT_NE(header.find(" W32 "), std::string::npos) << header;
    EXPECT_NE(header.find(" H32 "), std::string::npos) << header;
    EXPECT_NE(header.find(" F24:1"), std::string::npos) << header;

    // Bytes per frame from the chroma tag (4:2:0 unless it says 444).
    size_t frame_bytes = width * height * 3 / 2;
    if (header.find(" C444") != std::string::npos) frame_bytes = width * height * 3;

    // Walk FRAME markers and payloads: the whole of stdout must be header + F frames exactly.
    size_t at = eol + 1;
    int count = 0;
    while (at < data.size()) {
        ASSERT_EQ(data.compare(at, 5, "FRAME"), 0) << "expected FRAME at byte " << at << " (frame " << count << ")";
        size_t line_end = data.find('\n', at);
        ASSERT_NE(line_end, std::string::npos);
        at = line_end + 1 + frame_bytes;
        ASSERT_LE(at, data.size()) << "frame " << count << " is truncated";
        ++count;
    }
    EXPECT_EQ(count, frames);
    EXPECT_EQ(at, data.size());
    // No log line leaked into stdout, and the logs did go to stderr.
    EXPECT_EQ(data.find("slowlight:"), std::string::npos);
    EXPECT_NE(r.err.find("slowlight:"), std::string::npos) << r.err;

    // And a real decoder agrees.
    sl::VideoInfo v = sl::read_video(out);
    EXPECT_EQ(v.frames, frames);
    EXPECT_EQ(v.width, width);
    EXPECT_EQ(v.height, height);
    EXPECT_NEAR(v.fps, 24.0, 1e-6);
}
