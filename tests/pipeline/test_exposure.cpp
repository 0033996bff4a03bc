// The video's brightness does not depend on how it was rendered: resolution, passes, the number
// of sections K and the strategy leave the exposure within a few percent (a lamp covering 1 % of
// the image once moved it tenfold); `retime` exposes a pulse video as `render` does; a finished
// render resumed from its EXR frames exposes as the first run did; --exposure-percentile and
// --exposure-follow do what they say.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/pipeline/pipeline_helpers.h"

using namespace sl::test;

namespace {

// A cheap render of a sample; returns the exposure its --stats report.
double exposure_of(const ScratchDir& dir, const std::string& scene, int size, int passes,
                   std::vector<std::string> extra, int frames = 4) {
    const std::string stats = dir.file("stats.json");
    std::filesystem::remove(stats);
    extra.insert(extra.end(), {"--stats", stats, "-o", dir.file("out.mkv")});
    ProgramResult r = run_program(small_render(sample(scene), extra, frames, passes, 10000, size, size), "", 120);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    if (r.exit_code != 0) return 0;
    return read_json(stats).value("exposure", 0.0);
}

double exr_exposure(const std::string& path) {
    sl::ExrImage img = sl::read_exr(path);
    auto it = img.metadata.find("slowlight:exposure");
    return it == img.metadata.end() ? 0.0 : std::stod(it->second);
}

void expect_within(const std::vector<std::pair<std::string, double>>& runs, double tolerance) {
    ASSERT_FALSE(runs.empty());
    const double ref = runs.front().second;
    ASSERT_GT(ref, 0);
    for (const auto& [what, e] : runs) {
        testing::Test::RecordProperty(what, std::to_string(e));
        EXPECT_NEAR(e / ref, 1.0, tolerance) << what << ": exposure " << e << " against " << ref << " ("
                                             << runs.front().first << ")";
    }
}

}  // namespace

TEST(Exposure, ConstantEmissionHoldsAcrossResolutionPassesSectionsAndStrategy) {
    ScratchDir dir;
    const std::string box = "cornell_box.json";
    expect_within({{"128px K=1 8 passes", exposure_of(dir, box, 128, 8, {})},
                   {"256px K=1 8 passes", exposure_of(dir, box, 256, 8, {})},
                   {"128px K=2 8 passes", exposure_of(dir, box, 128, 8, {"--sections", "2"})},
                   {"128px K=4 8 passes", exposure_of(dir, box, 128, 8, {"--sections", "4"})},
                   {"128px frame-by-frame", exposure_of(dir, box, 128, 8, {"--strategy", "frame-by-frame"})},
                   {"128px K=1 16 passes", exposure_of(dir, box, 128, 16, {})},
                   {"128px K=1 32 passes", exposure_of(dir, box, 128, 32, {})}},
                  0.04);
}

TEST(Exposure, PulseHoldsAcrossResolutionPassesAndSections) {
    ScratchDir dir;
    const std::string box = "cornell_box_pulse.json";
    expect_within({{"128px K=1 8 passes", exposure_of(dir, box, 128, 8, {}, 8)},
                   {"256px K=1 8 passes", exposure_of(dir, box, 256, 8, {}, 8)},
                   {"128px K=2 8 passes", exposure_of(dir, box, 128, 8, {"--sections", "2"}, 8)},
                   {"128px K=4 8 passes", exposure_of(dir, box, 128, 8, {"--sections", "4"}, 8)},
                   {"128px K=1 32 passes", exposure_of(dir, box, 128, 32, {}, 8)}},
                  0.04);
}

// The pulse video made from a cube gets the render's own exposure (retime once used the
// steady image's and came out about 5x too dark).
TEST(Exposure, RetimedPulseVideoIsExposedAsTheRenderedOne) {
    ScratchDir dir;
    const std::string cube = dir.file("cube.npy");
    const double rendered =
        exposure_of(dir, "cornell_box.json", 64, 4, {"--emission", "pulse", "--cube", cube}, 8);
    ProgramResult r = run_program({"retime", cube, "--emission", "pulse", "--exr-dir", dir.file("re"), "-o",
                                   dir.file("re.mkv")});
    SL_EXPECT_EXIT(r, 0);
    const double retimed = exr_exposure(dir.file("re/frame_0000.exr"));
    EXPECT_NEAR(retimed / rendered, 1.0, 1e-4) << "render " << rendered << ", retime " << retimed;
    // And the constant video of the same cube, as a constant render of the scene would be.
    const double constant = exposure_of(dir, "cornell_box.json", 64, 4, {"--cube", cube}, 8);
    r = run_program({"retime", cube, "--exr-dir", dir.file("rc"), "-o", dir.file("rc.mkv")});
    SL_EXPECT_EXIT(r, 0);
    EXPECT_NEAR(exr_exposure(dir.file("rc/frame_0000.exr")) / constant, 1.0, 1e-4);

    // --exposure-follow too: frame by frame, the same exposures.
    const std::string cube2 = dir.file("cube2.npy");
    exposure_of(dir, "cornell_box.json", 64, 4,
                {"--emission", "pulse", "--exposure-follow", "--cube", cube2, "--exr-dir", dir.file("rf")}, 8);
    r = run_program({"retime", cube2, "--emission", "pulse", "--exposure-follow", "--exr-dir", dir.file("tf"), "-o",
                     dir.file("tf.mkv")});
    SL_EXPECT_EXIT(r, 0);
    for (int k = 0; k < 8; ++k) {
        const double a = exr_exposure(dir.file("rf/" + frame_name(k))), b = exr_exposure(dir.file("tf/" + frame_name(k)));
        ASSERT_GT(a, 0);
        EXPECT_NEAR(b / a, 1.0, 1e-4) << "frame " << k;
    }
}

// Resuming a finished render (nothing left to do) writes the video again at the same exposure,
// with one section (measured on the frames on disk) and with two (the same preview again).
TEST(Exposure, FinishedResumeIsExposedAsTheOriginalRun) {
    for (const char* k : {"1", "2"}) {
        SCOPED_TRACE(std::string("K = ") + k);
        ScratchDir dir;
        const std::vector<std::string> extra{"--sections", k, "--exr-dir", dir.file("exr")};
        const double first = exposure_of(dir, "cornell_box.json", 64, 4, extra, 6);
        std::vector<std::string> again = extra;
        again.push_back("--resume");
        const double resumed = exposure_of(dir, "cornell_box.json", 64, 4, again, 6);
        EXPECT_NEAR(resumed / first, 1.0, 1e-6) << "first " << first << ", resumed " << resumed;
        // The same holds for a pulse render, whose exposure comes from every frame.
        ScratchDir pd;
        const std::vector<std::string> pulse{"--sections", k, "--emission", "pulse", "--exr-dir", pd.file("exr")};
        const double p1 = exposure_of(pd, "cornell_box.json", 64, 4, pulse, 6);
        std::vector<std::string> p_again = pulse;
        p_again.push_back("--resume");
        EXPECT_NEAR(exposure_of(pd, "cornell_box.json", 64, 4, p_again, 6) / p1, 1.0, 1e-6);
    }
}

// --exposure-percentile P: P % of the pixels that do not see the lamp lie below white. Checked on
// the linear steady image and the exposure written into the frames' metadata.
TEST(Exposure, PercentileMapsThatShareOfPixelsBelowWhite) {
    ScratchDir dir;
    const std::string stats = dir.file("stats.json");
    ProgramResult r = run_program(small_render(sample("cornell_box.json"),
                                               {"--exposure-percentile", "90", "--exr-dir", dir.file("exr"), "--stats",
                                                stats, "-o", dir.file("v.mkv")},
                                               4, 4, 10000, 64, 64));
    SL_EXPECT_EXIT(r, 0);
    const double e = read_json(stats).value("exposure", 0.0);
    sl::ExrImage steady = sl::read_exr(dir.file("exr/steady.exr"));
    size_t below = 0, counted = 0;
    for (size_t p = 0; p < steady.rgb.size() / 3; ++p) {
        const double y = 0.2126 * steady.rgb[3 * p] + 0.7152 * steady.rgb[3 * p + 1] + 0.0722 * steady.rgb[3 * p + 2];
        if (y > 5) continue;  // the lamp (radiance 12 and more): left out by the rule
        ++counted;
        below += y * e < 1.0;
    }
    ASSERT_GT(counted, 1000u);
    EXPECT_NEAR(static_cast<double>(below) / static_cast<double>(counted), 0.90, 0.02) << "exposure " << e;
}

// --exposure-follow: a pulse's later, dimmer frames get more exposure, smoothly, never less than
// the fixed exposure; the displayed brightness of the fading tail stays within reach of the peak.
TEST(Exposure, FollowKeepsAFadingPulseReadableWithoutJumps) {
    ScratchDir dir;
    const int frames = 24;
    ProgramResult r = run_program(small_render(sample("cornell_box_pulse.json"),
                                               {"--exposure-follow", "--exr-dir", dir.file("exr"), "--stats",
                                                dir.file("s.json"), "-o", dir.file("v.mkv")},
                                               frames, 4, 20000, 48, 48));
    SL_EXPECT_EXIT(r, 0);
    const double base = read_json(dir.file("s.json")).value("exposure", 0.0);
    ASSERT_GT(base, 0);
    std::vector<double> e, shown;
    for (int k = 0; k < frames; ++k) {
        const std::string f = dir.file("exr/" + frame_name(k));
        e.push_back(exr_exposure(f));
        shown.push_back(e.back() * summarize_exr(f).mean);
    }
    for (int k = 0; k < frames; ++k) {
        EXPECT_GE(e[k], base * (1 - 1e-9)) << "frame " << k;
        if (k > 0) {
            EXPECT_LT(std::max(e[k], e[k - 1]) / std::min(e[k], e[k - 1]), 1.6) << "a jump at frame " << k;
        }
    }
    EXPECT_GT(e.back(), 2 * e[2]) << "the fading tail was not brightened";
    // (Frame 0 also holds the lamp itself, seen at t = 0.)
    const double peak = *std::max_element(shown.begin() + 1, shown.end());
    EXPECT_GT(shown.back(), peak / 8) << "the last frame is still far darker than the brightest";
}
