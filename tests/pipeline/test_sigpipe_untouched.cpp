// The renderer is a library too: writing a video to stdout must not change how the process
// answers SIGPIPE (that is main()'s choice). An in-process render into a pipe whose reader has
// gone still fails with an error, not by the signal, and leaves SIGPIPE as it found it.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "config/command_line.h"
#include "config/parse_scene.h"
#include "foundation/errors.h"
#include "pipeline/frame_outputs.h"
#include "pipeline/render_frames.h"
#include "tests/common/stdout_redirect.h"
#include "tests/pipeline/pipeline_helpers.h"

namespace sl::test {
namespace {

TEST(SigpipeUntouched, RenderingToAClosedStdoutLeavesTheDefaultAction) {
    struct sigaction dfl {};
    dfl.sa_handler = SIG_DFL;
    ASSERT_EQ(::sigaction(SIGPIPE, &dfl, nullptr), 0);  // a broken pipe would end this process
    sigset_t mask_before;
    ASSERT_EQ(::pthread_sigmask(SIG_SETMASK, nullptr, &mask_before), 0);

    ScratchDir dir;
    const std::vector<std::string> args = small_render(sample("cornell_box.json"), {}, 4, 2, 2000, 32, 32);
    std::vector<const char*> argv{"slowlight"};
    for (const std::string& a : args) argv.push_back(a.c_str());
    const RunOptions o = parse_command_line(static_cast<int>(argv.size()), argv.data());
    SceneDesc scene = parse_scene_file(sample("cornell_box.json"));
    apply_overrides(scene, o.overrides);
    RenderContext ctx(scene);

    OutputSettings s;
    s.video = "-";
    s.exr_dir = dir.file("exr");
    s.width = ctx.width;
    s.height = ctx.height;
    s.timeline = ctx.timeline;
    s.exposure = 1.0;

    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    ::close(fds[0]);  // the reader is gone before the first byte
    std::string error;
    {
        StdoutRedirect redirect(fds[1]);  // no assertion in here: gtest prints to stdout
        try {
            FrameOutputs out(s);
            render_frames(ctx, RenderRequest{}, out);
            out.finish();
        } catch (const RuntimeFailure& e) {
            error = e.what();
        }
    }
    ::close(fds[1]);
    EXPECT_NE(error.find("cannot write video stdout"), std::string::npos) << error;

    struct sigaction now {};
    ASSERT_EQ(::sigaction(SIGPIPE, nullptr, &now), 0);
    EXPECT_TRUE(now.sa_handler == SIG_DFL) << "SIGPIPE's disposition was changed";
    sigset_t mask_after, pending;
    ASSERT_EQ(::pthread_sigmask(SIG_SETMASK, nullptr, &mask_after), 0);
    EXPECT_EQ(sigismember(&mask_after, SIGPIPE), sigismember(&mask_before, SIGPIPE)) << "the signal mask was left changed";
    ASSERT_EQ(::sigpending(&pending), 0);
    EXPECT_FALSE(sigismember(&pending, SIGPIPE)) << "a SIGPIPE was left pending";
}

}  // namespace
}  // namespace sl::test
