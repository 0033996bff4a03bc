// A long render stopped by SIGINT/SIGTERM keeps what it paid for: every frame of the section in
// progress is written from the passes it completed, after the finished sections; the video
// plays, the EXRs are whole, the exit status is 130; --resume finishes it and the result
// equals an uninterrupted render.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>

#include "checkpoint_helpers.h"
#include "process.h"
#include "stages/output/exr_io.h"
#include "tests/common/video_reader.h"

namespace sl {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> long_render(const std::string& dir, const std::string& sub) {
    return test::render_into(dir, sub, {"--width", "48", "--height", "48", "--passes", "40", "--photons", "15000",
                                        "--frames", "8", "--sections", "4"});
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
    // The finished sections' frames got every pass, the interrupted section's fewer.
    int partial = 0;
    for (size_t k = 0; k < frames; ++k) {
        char name[64];
        std::snprintf(name, sizeof name, "/a/frame_%04zu.exr", k);
        ExrImage img = read_exr(dir + name);  // whole: it reads back
        EXPECT_EQ(img.width, 48);
        int passes = std::stoi(img.metadata.at("slowlight:passes"));
        EXPECT_GE(passes, 1);
        EXPECT_LE(passes, 40);
        if (img.metadata.count("slowlight:interrupted")) {
            EXPECT_LT(passes, 40);
            ++partial;
        } else {
            EXPECT_EQ(partial, 0) << "a finished section after an interrupted one";
            EXPECT_EQ(passes, 40);
        }
    }
    // (partial may be 0: the signal can land between two sections, before a pass of the next.)
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

// One section, interrupted after a few passes: all F frames are written, and they are exactly
// the frames of an uninterrupted render asked for that many passes (same seed).
TEST(Interrupt, OneSectionDeliversEveryFrameFromThePassesDone) {
    const std::string dir = test::fresh_dir("partial");
    auto args = [&](const std::string& sub, const std::string& passes) {
        return std::vector<std::string>{"render", "--width", "32", "--height", "24", "--frames", "6", "--passes", passes,
                                        "--photons", "3000", "--exr-dir", dir + "/" + sub, "-o", dir + "/" + sub + ".mkv",
                                        "--stats", dir + "/" + sub + ".json", "--checkpoint-every", "0", "--no-progress"};
    };
    test::Child c = test::spawn(args("a", "100000"), dir + "/err.txt");
    ASSERT_TRUE(test::wait_for(dir + "/a/section_0000.ckpt"));  // at least one pass done
    kill(c.pid, SIGINT);
    ASSERT_EQ(test::wait_exit(c), 130);
    const std::string err = test::read_text(dir + "/err.txt");

    nlohmann::json stats = test::read_json(dir + "/a.json");
    ASSERT_TRUE(stats.is_object()) << err;
    EXPECT_TRUE(stats["interrupted"].get<bool>());
    const int n = stats["passes_per_section"][0].get<int>();
    EXPECT_GE(n, 1);
    EXPECT_LT(n, 100000);
    EXPECT_EQ(stats["passes_reached"].get<int>(), n);
    // The message says what was written and how to continue.
    EXPECT_NE(err.find("wrote frames 0-5 (section 1 from " + std::to_string(n) + " of 100000 passes)"), std::string::npos)
        << err;
    EXPECT_NE(err.find("--resume"), std::string::npos) << err;

    VideoInfo v = read_video(dir + "/a.mkv");
    EXPECT_EQ(v.frames, 6);
    for (int k = 0; k < 6; ++k)
        EXPECT_EQ(read_exr(dir + "/a" + test::frame_name(k)).metadata.at("slowlight:passes"), std::to_string(n));

    test::RunResult b = test::run(args("b", std::to_string(n)), dir);
    ASSERT_EQ(b.status, 0) << b.err;
    test::expect_same_exrs(dir + "/a", dir + "/b", 6);
    EXPECT_EQ(v.mean_luma, read_video(dir + "/b.mkv").mean_luma) << "same frames, same exposure";
    fs::remove_all(dir);
}

// A pass of many photons is abandoned while they are traced (the buffer keeps the passes before
// it), so an interrupt does not wait for it: fewer photons were traced than the passes done plus
// one, and the frames equal a render of the passes done.
TEST(Interrupt, AbandonsAPassWhilePhotonsAreTraced) {
    const std::string dir = test::fresh_dir("abandon");
    auto args = [&](const std::string& sub, const std::string& passes) {
        return std::vector<std::string>{"render", "--width", "16", "--height", "16", "--frames", "3", "--passes", passes,
                                        "--photons", "1000000", "--exr-dir", dir + "/" + sub, "--stats",
                                        dir + "/" + sub + ".json", "--checkpoint-every", "0", "--no-progress"};
    };
    // The first pass's checkpoint is the event: the second pass's photons (a million, most of
    // its time) are being traced when the signal lands, on a fast machine or a loaded one.
    test::Child c = test::spawn(args("a", "1000"), dir + "/err.txt");
    ASSERT_TRUE(test::wait_for(dir + "/a/section_0000.ckpt"));
    kill(c.pid, SIGINT);
    ASSERT_EQ(test::wait_exit(c), 130);
    nlohmann::json s = test::read_json(dir + "/a.json");
    const int n = s["passes_per_section"][0].get<int>();
    const bool abandoned = s["photons_traced"].get<int64_t>() < int64_t(n + 1) * 1000000;
    EXPECT_TRUE(abandoned) << "the pass in flight was finished";
    ASSERT_GE(n, 1);
    test::RunResult b = test::run(args("b", std::to_string(n)), dir);
    ASSERT_EQ(b.status, 0) << b.err;
    test::expect_same_exrs(dir + "/a", dir + "/b", 3);
    fs::remove_all(dir);
}

// A signal during set-up (here: while a large mesh is being read) ends the run at once with
// exit 130 and nothing written.
TEST(Interrupt, DuringSetUpWritesNothing) {
    const std::string dir = test::fresh_dir("setup");
    {
        std::ofstream obj(dir + "/big.obj");
        const int n = 400;  // a 400x400 grid: 320 000 triangles, a few seconds to read and build
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j) obj << "v " << i * 0.001 << " 0.0 " << j * 0.001 << "\n";
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                int a = i * (n + 1) + j + 1, b = a + 1, c2 = a + n + 1, d = c2 + 1;
                obj << "f " << a << ' ' << b << ' ' << d << "\nf " << a << ' ' << d << ' ' << c2 << "\n";
            }
    }
    std::ofstream(dir + "/scene.json") << R"({
        "camera": {"position": [0, 1, 3], "look_at": [0, 0, 0], "width": 16, "height": 16},
        "materials": {"w": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
        "shapes": [{"type": "mesh", "file": "big.obj", "material": "w"}],
        "lights": [{"type": "point", "position": [0, 1.5, 0], "power": [1, 1, 1]}],
        "time": {"start_ns": 0, "end_ns": 10, "frames": 2},
        "render": {"passes": 2, "photons_per_pass": 100}})";
    test::Child c = test::spawn({"render", dir + "/scene.json", "-o", dir + "/out.mkv", "--exr-dir", dir + "/exr",
                                 "--stats", dir + "/s.json", "--no-progress"},
                                dir + "/err.txt");
    // Wait until the program has its handlers (it is then setting up), then signal.
    for (int i = 0; i < 5000; ++i) {
        std::ifstream status("/proc/" + std::to_string(c.pid) + "/status");
        std::string line;
        bool ready = false;
        while (std::getline(status, line))
            if (line.rfind("SigCgt:", 0) == 0) ready = (std::stoull(line.substr(7), nullptr, 16) >> (SIGTERM - 1)) & 1;
        if (ready) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    kill(c.pid, SIGTERM);
    EXPECT_EQ(test::wait_exit(c), 130);
    const std::string err = test::read_text(dir + "/err.txt");
    EXPECT_NE(err.find("interrupted during set-up; nothing written"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(dir + "/out.mkv"));
    EXPECT_FALSE(fs::exists(dir + "/exr"));
    EXPECT_FALSE(fs::exists(dir + "/s.json"));
    for (auto& e : fs::directory_iterator(dir)) EXPECT_NE(e.path().filename().string()[0], '.') << "temporary file left";
    fs::remove_all(dir);
}

TEST(Interrupt, SecondSignalExitsAtOnceWithoutBrokenFiles) {
    std::string dir = test::fresh_dir("twice");
    test::Child c = test::spawn(long_render(dir, "a"), dir + "/err.txt");
    ASSERT_TRUE(wait_for_file(dir + "/a/frame_0000.exr"));
    kill(c.pid, SIGINT);
    kill(c.pid, SIGINT);
    auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(test::wait_exit(c, 10), 130);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
    for (auto& e : fs::directory_iterator(dir + "/a")) {
        if (e.path().extension() == ".exr") {
            EXPECT_NO_THROW(read_exr(e.path().string())) << e.path();
        }
    }
    // The video is either closed and playable or absent; never a truncated file under its name.
    if (fs::exists(dir + "/a.mkv")) {
        EXPECT_GT(read_video(dir + "/a.mkv").frames, 0);
    }
    // And no temporary is left behind (the second signal removes every live one).
    for (const std::string& d : {dir, dir + "/a"})
        for (auto& e : fs::directory_iterator(d))
            EXPECT_NE(e.path().filename().string().rfind(".slowlight-tmp-", 0), 0u) << e.path();
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
