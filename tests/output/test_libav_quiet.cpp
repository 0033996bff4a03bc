// libav's and x264's own log lines never reach stderr (which carries our progress and the one
// `error:` line) unless SLOWLIGHT_AV_LOG asks for them. x264 logs through av_log, so an error
// logged there after the encoder is opened must print nothing.
#include <gtest/gtest.h>

extern "C" {
#include <libavutil/log.h>
}

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "stages/output/video_encoder.h"
#include "tests/common/temp_dir.h"

namespace {

TEST(LibavLogs, SilentUnlessAskedFor) {
    ASSERT_EQ(std::getenv("SLOWLIGHT_AV_LOG"), nullptr) << "the test needs the default";
    sl::test::TempDir dir;
    auto enc = sl::VideoEncoder::open({.path = dir.file("v.mp4"), .width = 16, .height = 16});
    // Capture stderr while libav logs at error level, as it does on a failing write.
    std::fflush(stderr);
    const std::string captured = dir.file("stderr.txt");
    int saved = ::dup(2);
    std::FILE* f = std::fopen(captured.c_str(), "w");
    ASSERT_TRUE(f);
    ::dup2(::fileno(f), 2);
    av_log(nullptr, AV_LOG_ERROR, "a libav error line\n");
    av_log(nullptr, AV_LOG_WARNING, "a libav warning line\n");
    std::fflush(stderr);
    ::dup2(saved, 2);
    ::close(saved);
    std::fclose(f);
    std::FILE* in = std::fopen(captured.c_str(), "r");
    char buf[256] = {};
    size_t n = std::fread(buf, 1, sizeof buf - 1, in);
    std::fclose(in);
    EXPECT_EQ(n, 0u) << buf;
    enc->finish();
}

}  // namespace
