// Hostile files around a run: outputs that are links, FIFOs or descriptors; temporaries left
// by killed runs; EXR frames forged or damaged before --resume. (The one-line cases, such as
// outputs colliding with inputs, are rows of docs/bad-inputs.md.)
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "process.h"
#include "stages/output/exr_frame_check.h"
#include "stages/output/exr_io.h"

namespace sl {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> small_render(std::vector<std::string> extra) {
    std::vector<std::string> a = {"render", "--width", "16", "--height", "16", "--passes", "2", "--photons", "2000",
                                  "--frames", "4", "--no-progress"};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
}

std::string slurp(const std::string& path) { return test::read_text(path); }

bool is_link(const std::string& p) { return fs::is_symlink(fs::symlink_status(p)); }

TEST(HostileOutputs, LinksAreWrittenThroughAndSpecialFilesInPlace) {
    std::string dir = test::fresh_dir("links");
    fs::create_directories(dir + "/real");
    fs::create_symlink("real/stats.json", dir + "/stats_link.json");       // to a file not there yet
    fs::create_symlink("/proc/self/fd/1", dir + "/stdout_link");           // like /dev/stdout
    fs::create_directories(dir + "/exr");
    fs::create_symlink("../real/frame0.exr", dir + "/exr/frame_0000.exr");  // a frame through a link
    ASSERT_EQ(mkfifo((dir + "/stats.fifo").c_str(), 0644), 0);
    std::string from_fifo;
    std::thread reader([&] { from_fifo = slurp(dir + "/stats.fifo"); });

    // stdout is a regular file: a rename onto the link would have replaced the link.
    test::Child c = test::spawn(small_render({"--stats", dir + "/stats_link.json", "--exr-dir", dir + "/exr"}),
                                dir + "/err1.txt");
    EXPECT_EQ(test::wait_exit(c), 0) << slurp(dir + "/err1.txt");
    c = test::spawn(small_render({"--stats", dir + "/stats.fifo"}), dir + "/err2.txt");
    int status = test::wait_exit(c);
    ::close(::open((dir + "/stats.fifo").c_str(), O_WRONLY | O_NONBLOCK));  // a failed run: release the reader
    reader.join();
    ASSERT_EQ(status, 0) << slurp(dir + "/err2.txt");
    c = test::spawn(small_render({"--stats", dir + "/stdout_link"}), dir + "/err3.txt", dir + "/stdout.txt");
    ASSERT_EQ(test::wait_exit(c), 0) << slurp(dir + "/err3.txt");

    EXPECT_TRUE(is_link(dir + "/stats_link.json"));
    EXPECT_EQ(nlohmann::json::parse(slurp(dir + "/real/stats.json"))["frames"], 4);
    EXPECT_TRUE(is_link(dir + "/exr/frame_0000.exr"));
    EXPECT_EQ(read_exr(dir + "/real/frame0.exr").width, 16);
    EXPECT_TRUE(fs::is_fifo(fs::symlink_status(dir + "/stats.fifo")));
    EXPECT_EQ(nlohmann::json::parse(from_fifo)["frames"], 4);
    EXPECT_TRUE(is_link(dir + "/stdout_link"));
    EXPECT_EQ(nlohmann::json::parse(slurp(dir + "/stdout.txt"))["frames"], 4);
    for (auto& e : fs::recursive_directory_iterator(dir))
        EXPECT_NE(e.path().filename().string().rfind(".slowlight-tmp-", 0), 0u) << e.path();
    fs::remove_all(dir);
}

TEST(HostileOutputs, VideoIntoAFifoIsStreamedInPlace) {
    std::string dir = test::fresh_dir("video_fifo");
    const std::string fifo = dir + "/video_pipe";  // no extension: a FIFO is Matroska
    ASSERT_EQ(mkfifo(fifo.c_str(), 0644), 0);
    std::string bytes;
    std::thread reader([&] { bytes = slurp(fifo); });
    test::RunResult r = test::run(small_render({"-o", fifo}), dir);
    ::close(::open(fifo.c_str(), O_WRONLY | O_NONBLOCK));  // should the run have failed: release the reader
    reader.join();
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::is_fifo(fs::symlink_status(fifo)));
    EXPECT_EQ(bytes.substr(0, 4), std::string("\x1a\x45\xdf\xa3", 4));  // Matroska's EBML magic
    fs::remove_all(dir);
}

pid_t dead_pid() {
    pid_t p = fork();
    if (p == 0) _exit(0);
    waitpid(p, nullptr, 0);
    return p;  // reaped: no such process any more
}

TEST(HostileOutputs, TemporariesOfKilledRunsAreRemoved) {
    std::string dir = test::fresh_dir("stale");
    fs::create_directories(dir + "/exr");
    const std::string dead = ".slowlight-tmp-" + std::to_string(dead_pid()) + "-0-";
    const std::string alive = ".slowlight-tmp-" + std::to_string(getpid()) + "-0-";
    for (const std::string& name : {dir + "/" + dead + "v.mkv", dir + "/exr/" + dead + "frame_0001.exr",
                                    dir + "/" + alive + "v.mkv"})
        std::ofstream(name) << "half written";
    test::RunResult r = test::run(small_render({"-o", dir + "/v.mkv", "--exr-dir", dir + "/exr"}), dir);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/" + dead + "v.mkv"));
    EXPECT_FALSE(fs::exists(dir + "/exr/" + dead + "frame_0001.exr"));
    EXPECT_TRUE(fs::exists(dir + "/" + alive + "v.mkv")) << "a running writer's temporary is not stale";
    fs::remove_all(dir);
}

// --resume after each forgery re-renders the forged frame's section, with a warning naming the
// file, and ends with exactly the frames of the first render.
TEST(HostileResume, ForgedOrDamagedFramesAreRenderedAgain) {
    std::string dir = test::fresh_dir("forged");
    auto args = small_render({"--sections", "2", "--exr-dir", dir + "/x"});
    ASSERT_EQ(test::run(args, dir).status, 0);
    std::vector<ExrImage> good;
    auto frame = [&](int k) {
        char name[32];
        std::snprintf(name, sizeof name, "/x/frame_%04d.exr", k);
        return dir + name;
    };
    for (int k = 0; k < 4; ++k) good.push_back(read_exr(frame(k)));
    fs::copy(dir + "/x", dir + "/original", fs::copy_options::recursive);
    args.push_back("--resume");

    struct Forgery {
        const char* what;
        int frame;
        std::function<void(const std::string&)> apply;
    };
    const std::vector<Forgery> forgeries = {
        {"1x1 image with the fingerprint copied", 2,
         [&](const std::string& p) { write_exr(p, 1, 1, std::vector<float>{1, 1, 1}.data(), good[2].metadata); }},
        {"another frame copied onto its name", 1, [&](const std::string& p) { fs::copy_file(frame(0), p, fs::copy_options::overwrite_existing); }},
        {"NaN pixel, checksum recomputed", 3,
         [&](const std::string& p) {
             ExrImage img = good[3];
             img.rgb[5] = std::nanf("");
             img.metadata[kChecksumKey] = pixel_checksum(img.rgb.data(), img.rgb.size());
             write_exr(p, 16, 16, img.rgb.data(), img.metadata);
         }},
        {"negative pixel, checksum recomputed", 3,
         [&](const std::string& p) {
             ExrImage img = good[3];
             img.rgb[7] = -1;
             img.metadata[kChecksumKey] = pixel_checksum(img.rgb.data(), img.rgb.size());
             write_exr(p, 16, 16, img.rgb.data(), img.metadata);
         }},
        {"pixel edited, checksum kept", 0,
         [&](const std::string& p) {
             ExrImage img = good[0];
             img.rgb[100] *= 2;
             write_exr(p, 16, 16, img.rgb.data(), img.metadata);
         }},
        {"half-float channels", 0,
         [&](const std::string& p) { write_exr(p, 16, 16, good[0].rgb.data(), good[0].metadata, /*half*/ true); }},
    };
    for (const Forgery& f : forgeries) {
        SCOPED_TRACE(f.what);
        fs::remove_all(dir + "/x");
        fs::copy(dir + "/original", dir + "/x", fs::copy_options::recursive);
        f.apply(frame(f.frame));
        test::RunResult r = test::run(args, dir, 120);
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_NE(r.err.find("warning: --resume: " + frame(f.frame)), std::string::npos) << r.err;
        for (int k = 0; k < 4; ++k) EXPECT_EQ(read_exr(frame(k)).rgb, good[k].rgb) << "frame " << k;
    }
    fs::remove_all(dir);
}

}  // namespace
}  // namespace sl
