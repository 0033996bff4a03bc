// `slowlight render -o - | player` where the player quits early: the video ends, the render does
// not. The other outputs are completed, then one `error:` line and exit status 1 (never death by
// SIGPIPE, whose disposition the program leaves alone).
#include <gtest/gtest.h>
#include <fcntl.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "checkpoint_helpers.h"
#include "process.h"
#include "stages/output/exr_io.h"

namespace sl {
namespace {

namespace fs = std::filesystem;

TEST(ClosedPipe, AReaderThatQuitsEndsTheVideoWithOneErrorAndTheFramesComplete) {
    const std::string dir = test::fresh_dir("closed_pipe");
    int fds[2];
    ASSERT_EQ(::pipe2(fds, O_CLOEXEC), 0);
    // One page of pipe: the 8 frames (27 KiB of YUV4MPEG2) cannot all fit before the reader goes.
    ASSERT_GT(::fcntl(fds[1], F_SETPIPE_SZ, 4096), 0);
    const int frames = 8;
    test::Child c = test::spawn({"render", "--width", "48", "--height", "48", "--frames", std::to_string(frames), "--passes",
                                 "2", "--photons", "2000", "--exr-dir", dir + "/exr", "-o", "-", "--no-progress"},
                                dir + "/err.txt", "", fds[1]);
    ::close(fds[1]);
    char head[9] = {};
    const ssize_t got = ::read(fds[0], head, sizeof head);  // waits for the stream to begin
    ::close(fds[0]);                                        // then the reader quits
    EXPECT_EQ(std::string(head, got > 0 ? size_t(got) : 0), "YUV4MPEG2");

    EXPECT_EQ(test::wait_exit(c, 120), 1);
    const std::string err = test::read_text(dir + "/err.txt");
    const std::vector<std::string> errors = test::error_lines(err);
    ASSERT_EQ(errors.size(), 1u) << err;
    EXPECT_NE(errors[0].find("cannot write video stdout"), std::string::npos) << err;
    for (int k = 0; k < frames; ++k) EXPECT_NO_THROW(read_exr(dir + "/exr" + test::frame_name(k))) << k;
    EXPECT_NO_THROW(read_exr(dir + "/exr/steady.exr"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace sl
