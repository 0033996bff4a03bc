// FrameOutputs hands each tone-mapped frame to the video encoder on a task of its own and goes
// on with the next frame: the video must still hold every frame, in order, and a failing
// encoder must still end the run with its error (after the other outputs are complete).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "foundation/errors.h"
#include "pipeline/frame_outputs.h"
#include "tests/common/stdout_redirect.h"
#include "tests/common/temp_dir.h"
#include "tests/common/video_reader.h"

namespace {

constexpr int kWidth = 48, kHeight = 32, kFrames = 9;

sl::OutputSettings settings_for(const std::string& video) {
    sl::OutputSettings s;
    s.video = video;
    s.width = kWidth;
    s.height = kHeight;
    s.timeline.frames = kFrames;
    s.exposure = 1.0;  // no metering: the frames' levels reach the video as they are
    return s;
}

// Frame k: a flat grey whose level rises with k (linear light; the curve maps it monotonically).
std::vector<float> grey(int k) { return std::vector<float>(size_t(kWidth) * kHeight * 3, 0.05f + 0.1f * float(k)); }

TEST(FrameOutputs, TheVideoHoldsEveryFrameInOrder) {
    sl::test::TempDir dir;
    const std::string path = dir.file("frames.mkv");  // FFV1: lossless, so levels compare exactly
    {
        sl::FrameOutputs out(settings_for(path));
        for (int k = 0; k < kFrames; ++k) out.write_frame(k, grey(k));
        out.finish();  // waits for the frame still being encoded before closing the file
        EXPECT_EQ(out.frames_written, kFrames);
    }
    const sl::VideoInfo info = sl::read_video(path);
    ASSERT_EQ(info.frames, kFrames);  // the last frame, encoded while finish() began, is there
    ASSERT_EQ(info.mean_luma.size(), size_t(kFrames));
    for (int k = 1; k < kFrames; ++k)
        EXPECT_GT(info.mean_luma[size_t(k)], info.mean_luma[size_t(k - 1)] + 1.0) << "frame " << k;
}

TEST(FrameOutputs, AFailingEncoderEndsTheRunWithItsError) {
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    ::close(fds[0]);  // nobody reads: every write of the y4m stream fails (EPIPE)
    std::string error;
    int frames_before_error = -1;
    {
        sl::test::StdoutRedirect redirect(fds[1]);  // gtest prints to stdout: nothing is asserted in here
        try {
            sl::FrameOutputs out(settings_for("-"));
            for (int k = 0; k < kFrames; ++k) {
                out.write_frame(k, grey(k));
                frames_before_error = k + 1;
            }
            out.finish();
        } catch (const sl::RuntimeFailure& e) {
            error = e.what();
        }
    }
    ::close(fds[1]);
    EXPECT_NE(error.find("cannot write video"), std::string::npos) << error;
    // The encoder runs one frame behind: its failure on frame k is reported by the next call.
    EXPECT_LE(frames_before_error, 2);
}

// A reader that goes away ends the video, not the run: every EXR frame is still written, and
// the video's failure is reported once the others are complete.
TEST(FrameOutputs, AClosedPipeEndsOnlyTheVideo) {
    sl::test::TempDir dir;
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    ::close(fds[0]);
    sl::OutputSettings s = settings_for("-");
    s.exr_dir = dir.file("exr");
    std::string error;
    int frames_written = -1;
    {
        sl::test::StdoutRedirect redirect(fds[1]);
        try {
            sl::FrameOutputs out(s);
            for (int k = 0; k < kFrames; ++k) out.write_frame(k, grey(k));
            frames_written = int(out.frames_written);
            out.finish();
        } catch (const sl::RuntimeFailure& e) {
            error = e.what();
        }
    }
    ::close(fds[1]);
    EXPECT_EQ(frames_written, kFrames);
    EXPECT_NE(error.find("cannot write video stdout"), std::string::npos) << error;
    for (int k = 0; k < kFrames; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%04d.exr", k);
        EXPECT_TRUE(std::filesystem::exists(dir.path() / "exr" / name)) << name;
    }
}

}  // namespace
