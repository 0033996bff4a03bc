// The transient cube holds the whole time-resolved stack; `retime` makes constant and pulse
// videos from it without rendering again: equal to a fresh render with the cube's own
// emission, and for another emission the same light (a fresh pulse render samples a quad's
// direct light frame by frame, so its frames are smoother than a constant cube's pulse).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>

#include "process.h"
#include "stages/output/exr_io.h"
#include "stages/output/npy_cube.h"
#include "tests/common/video_reader.h"

namespace sl {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> scene_args(const std::string& dir) {
    // 12 frames of 2 ns over the Cornell box: pulse:4 is two frames wide.
    return {"render", "--width", "32", "--height", "24", "--passes", "3", "--photons", "8000", "--frames", "12",
            "--no-progress"};
}

double seconds(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void expect_frames_close(const std::string& a, const std::string& b, int frames) {
    for (int k = 0; k < frames; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "/frame_%04d.exr", k);
        ExrImage x = read_exr(a + name), y = read_exr(b + name);
        ASSERT_EQ(x.rgb.size(), y.rgb.size());
        for (size_t i = 0; i < x.rgb.size(); ++i)
            ASSERT_NEAR(x.rgb[i], y.rgb[i], 1e-4f * (1 + std::abs(y.rgb[i]))) << name << " value " << i;
    }
}

TEST(Cube, RetimeEqualsFreshRendersOfEachEmission) {
    std::string dir = test::fresh_dir("cube");
    auto args = scene_args(dir);
    args.insert(args.end(), {"--cube", dir + "/c.npy", "--exr-dir", dir + "/constant"});
    auto t0 = std::chrono::steady_clock::now();
    test::RunResult r = test::run(args, dir);
    double render_s = seconds(t0);
    ASSERT_EQ(r.status, 0) << r.err;

    // The file is a NumPy array of shape (frames + 2, height, width, 3), float32.
    NpyCube cube = read_npy_cube(dir + "/c.npy");
    EXPECT_EQ(cube.planes, 14);
    EXPECT_EQ(cube.height, 24);
    EXPECT_EQ(cube.width, 32);
    EXPECT_TRUE(fs::exists(dir + "/c.npy.json"));

    // Constant emission again, from the cube alone.
    t0 = std::chrono::steady_clock::now();
    test::RunResult rc = test::run({"retime", dir + "/c.npy", "--exr-dir", dir + "/re_constant", "-o", dir + "/re.mkv"}, dir);
    double retime_s = seconds(t0);
    ASSERT_EQ(rc.status, 0) << rc.err;
    expect_frames_close(dir + "/re_constant", dir + "/constant", 12);
    EXPECT_EQ(read_video(dir + "/re.mkv").frames, 12);

    // A pulse two frames wide from the constant render's cube: each frame is the light of its two
    // buckets, the difference of the constant frames two apart (nothing arrives before t = 0).
    ASSERT_EQ(test::run({"retime", dir + "/c.npy", "--emission", "pulse:4", "--exr-dir", dir + "/re_pulse"}, dir).status, 0);
    for (int k = 0; k < 12; ++k) {
        char name[32], back[32];
        std::snprintf(name, sizeof name, "/frame_%04d.exr", k);
        std::snprintf(back, sizeof back, "/frame_%04d.exr", k - 2);
        const ExrImage p = read_exr(dir + "/re_pulse" + name), c = read_exr(dir + "/constant" + name);
        const ExrImage c2 = k >= 2 ? read_exr(dir + "/constant" + back) : ExrImage{};
        ASSERT_EQ(p.rgb.size(), c.rgb.size());
        for (size_t i = 0; i < p.rgb.size(); ++i) {
            const float want = c.rgb[i] - (k >= 2 ? c2.rgb[i] : 0.0f);
            ASSERT_NEAR(p.rgb[i], want, 1e-4f * (1 + std::abs(c.rgb[i]))) << name << " value " << i;
        }
    }
    // A fresh pulse render of the same seed sees the same photons, but takes the lamp's direct
    // light frame by frame (direct_by_frames.h): its own cube retimed gives its frames exactly,
    // and the constant cube's pulse has the same frame means within the lamp's sampling noise.
    auto fresh = scene_args(dir);
    fresh.insert(fresh.end(), {"--emission", "pulse:4", "--exr-dir", dir + "/pulse", "--cube", dir + "/p.npy"});
    test::RunResult rp = test::run(fresh, dir);
    ASSERT_EQ(rp.status, 0) << rp.err;
    ASSERT_EQ(test::run({"retime", dir + "/p.npy", "--emission", "pulse:4", "--exr-dir", dir + "/re_pulse2"}, dir).status, 0);
    expect_frames_close(dir + "/re_pulse2", dir + "/pulse", 12);
    for (int k = 2; k < 12; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "/frame_%04d.exr", k);
        const ExrImage a = read_exr(dir + "/re_pulse" + name), b = read_exr(dir + "/pulse" + name);
        double ma = 0, mb = 0;
        for (size_t i = 0; i < a.rgb.size(); ++i) ma += a.rgb[i], mb += b.rgb[i];
        EXPECT_NEAR(ma, mb, 0.05 * mb) << name;
    }

    std::printf("render with cube: %.2f s, retime: %.2f s (%.0f%%)\n", render_s, retime_s, 100 * retime_s / render_s);
    fs::remove_all(dir);
}

TEST(Cube, RetimeRefusesAPulseThatIsNotWholeBuckets) {
    std::string dir = test::fresh_dir("cube_bad");
    auto args = scene_args(dir);
    args.insert(args.end(), {"--cube", dir + "/c.npy"});
    ASSERT_EQ(test::run(args, dir).status, 0);
    test::RunResult r = test::run({"retime", dir + "/c.npy", "--emission", "pulse:3", "-o", dir + "/x.mp4"}, dir);
    EXPECT_EQ(r.status, 2);
    ASSERT_EQ(test::error_lines(r.err).size(), 1u) << r.err;
    // The same whole-frames check, and words, as a scene's pulse width (the Timeline's).
    EXPECT_NE(r.err.find("--emission: pulse width 3 ns is not a whole multiple of the frame width"), std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir + "/x.mp4"));
    fs::remove_all(dir);
}

// A cube in mitransient's order (height, width, time, 3) is a valid .npy of another shape: retime
// must tell it by its side-car, not read its rows as time planes.
TEST(Cube, RetimeRefusesACubeInMitransientsOrder) {
    std::string dir = test::fresh_dir("cube_mitransient");
    auto args = scene_args(dir);
    args.insert(args.end(), {"--cube", dir + "/m.npy", "--cube-layout", "mitransient"});
    test::RunResult made = test::run(args, dir);
    ASSERT_EQ(made.status, 0) << made.err;
    NpyCube cube = read_npy_cube(dir + "/m.npy");  // read as (planes, height, width, 3): rows, columns, frames
    EXPECT_EQ(cube.planes, 24);
    EXPECT_EQ(cube.height, 32);
    EXPECT_EQ(cube.width, 12);
    test::RunResult r = test::run({"retime", dir + "/m.npy", "-o", dir + "/x.mp4"}, dir);
    EXPECT_EQ(r.status, 2);
    ASSERT_EQ(test::error_lines(r.err).size(), 1u) << r.err;
    EXPECT_NE(r.err.find("key 'cube_layout': retime reads cubes in slowlight's order"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/x.mp4"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace sl
