// A long render stopped by SIGINT/SIGTERM keeps what it paid for: the frames in hand are
// written, the video plays, the EXRs are whole, the exit status is 130; --resume finishes it
// and the result equals an uninterrupted render.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>

#include "process.h"
#include "stages/output/exr_io.h"
#include "stages/output/video_reader.h"

namespace sl {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> long_render(const std::string& dir, const std::string& sub) {
    return {"render", "--width", "48", "--height", "48", "--passes", "40", "--photons", "15000", "--frames", "8",
            "--sections", "4", "--exr-dir", dir + "/" + sub, "-o", dir + "/" + sub + ".mkv", "--no-progress"};
}

// Waits until `path` exists (the render has finished its first section), at most 120 s.
bool wait_for_file(const std::string& path) {
    for (int i = 0; i < 6000; ++i) {
        if (fs::exists(path)) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
}

size_t count_frames(const std::string& dir) {
    size_t n = 0;
    for (auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().rfind("frame_", 0) == 0;
    return n;
}

class Interrupt : public ::testing::TestWithParam<int> {};

TEST_P(Interrupt, WritesFramesInHandClosesTheVideoAndExits130) {
    const int sig = GetParam();
    std::string dir = test::fresh_dir(sig == SIGINT ? "sigint" : "sigterm");
    test::Child c = test::spawn(long_render(dir, "a"), dir + "/err.txt");
    ASSERT_TRUE(wait_for_file(dir + "/a/frame_0001.exr"));
    kill(c.pid, sig);
    EXPECT_EQ(test::wait_exit(c), 130) << test::read_text(dir + "/err.txt");
    size_t frames = count_frames(dir + "/a");
    EXPECT_GE(frames, 2u);
    EXPECT_LT(frames, 8u) << "the render was meant to be stopped before the end";
    // Whole sections only: the frame count is where one of the announced sections ends
    // ("slowlight: section s/K, frames a-b: ...").
    std::set<size_t> section_ends;
    std::istringstream log(test::read_text(dir + "/err.txt"));
    for (std::string line; std::getline(log, line);) {
        size_t at = line.find(", frames ");
        unsigned first = 0, last = 0;
        if (at != std::string::npos && std::sscanf(line.c_str() + at, ", frames %u-%u", &first, &last) == 2)
            section_ends.insert(last + 1);
    }
    EXPECT_EQ(section_ends.count(frames), 1u) << "whole sections only: " << frames << " frames";
    for (size_t k = 0; k < frames; ++k) {
        char name[64];
        std::snprintf(name, sizeof name, "/a/frame_%04zu.exr", k);
        ExrImage img = read_exr(dir + name);  // whole: it reads back
        EXPECT_EQ(img.width, 48);
    }
    VideoInfo v = read_video(dir + "/a.mkv");  // closed properly: it decodes
    EXPECT_EQ(v.frames, static_cast<int64_t>(frames));
    std::string probe = "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 " +
                        dir + "/a.mkv > " + dir + "/probe.txt 2>&1";
    ASSERT_EQ(std::system(probe.c_str()), 0);
    EXPECT_EQ(std::stoi(test::read_text(dir + "/probe.txt")), static_cast<int>(frames));
    for (auto& e : fs::directory_iterator(dir)) EXPECT_NE(e.path().filename().string()[0], '.') << "temporary file left";
    fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Signals, Interrupt, ::testing::Values(SIGINT, SIGTERM));

TEST(Interrupt, SecondSignalExitsAtOnceWithoutBrokenFiles) {
    std::string dir = test::fresh_dir("twice");
    test::Child c = test::spawn(long_render(dir, "a"), dir + "/err.txt");
    ASSERT_TRUE(wait_for_file(dir + "/a/frame_0000.exr"));
    kill(c.pid, SIGINT);
    kill(c.pid, SIGINT);
    auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(test::wait_exit(c, 10), 130);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
    for (auto& e : fs::directory_iterator(dir + "/a")) EXPECT_NO_THROW(read_exr(e.path().string())) << e.path();
    // The video is either closed and playable or absent; never a truncated file under its name.
    if (fs::exists(dir + "/a.mkv")) {
        EXPECT_GT(read_video(dir + "/a.mkv").frames, 0);
    }
    fs::remove_all(dir);
}

TEST(Resume, FinishesAnInterruptedRenderExactly) {
    std::string dir = test::fresh_dir("resume");
    test::Child c = test::spawn(long_render(dir, "a"), dir + "/err.txt");
    ASSERT_TRUE(wait_for_file(dir + "/a/frame_0001.exr"));
    kill(c.pid, SIGTERM);
    ASSERT_EQ(test::wait_exit(c), 130);
    size_t kept = count_frames(dir + "/a");
    ASSERT_GE(kept, 2u);

    std::vector<std::string> args = long_render(dir, "a");
    args.push_back("--resume");
    test::RunResult resumed = test::run(args, dir);
    ASSERT_EQ(resumed.status, 0) << resumed.err;
    EXPECT_NE(resumed.err.find("resumed"), std::string::npos);
    EXPECT_EQ(read_video(dir + "/a.mkv").frames, 8);

    test::RunResult fresh = test::run(long_render(dir, "b"), dir);
    ASSERT_EQ(fresh.status, 0) << fresh.err;
    for (int k = 0; k < 8; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "/frame_%04d.exr", k);
        // Renders are deterministic for a seed, so the resumed frames are the very same.
        EXPECT_EQ(read_exr(dir + "/a" + name).rgb, read_exr(dir + "/b" + name).rgb) << name;
    }
    EXPECT_EQ(read_exr(dir + "/a/steady.exr").rgb, read_exr(dir + "/b/steady.exr").rgb);
    fs::remove_all(dir);
}

TEST(Resume, RefusesFramesOfAnotherSceneOrSettings) {
    std::string dir = test::fresh_dir("resume_other");
    std::vector<std::string> a = {"render", "--width", "24", "--height", "24", "--passes", "2", "--photons", "2000",
                                  "--frames", "4", "--exr-dir", dir + "/x", "--no-progress"};
    ASSERT_EQ(test::run(a, dir).status, 0);
    std::vector<std::string> b = a;
    b[6] = "3";  // other passes: other pixels
    b.push_back("--resume");
    test::RunResult r = test::run(b, dir);
    EXPECT_EQ(r.status, 2);
    auto errors = test::error_lines(r.err);
    ASSERT_EQ(errors.size(), 1u) << r.err;
    EXPECT_NE(errors[0].find("different scene or settings"), std::string::npos) << errors[0];
    fs::remove_all(dir);
}

}  // namespace
}  // namespace sl
