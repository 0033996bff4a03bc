// The real program renders every shipped sample, and the default demo behaves like a light
// switched on in a dark room: it starts dark and approaches the steady state.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "tests/pipeline/pipeline_helpers.h"

namespace fs = std::filesystem;
using namespace sl::test;

namespace {

// Per-pixel luminance (Rec. 709 weights) of interleaved linear RGB.
std::vector<double> luminance(const std::vector<float>& rgb) {
    std::vector<double> y(rgb.size() / 3);
    for (size_t p = 0; p < y.size(); ++p)
        y[p] = 0.2126 * rgb[p * 3] + 0.7152 * rgb[p * 3 + 1] + 0.0722 * rgb[p * 3 + 2];
    return y;
}

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

}  // namespace

TEST(RenderSamples, EverySampleRendersSmallAndQuick) {
    const std::vector<std::string> scenes = sample_scenes();
    ASSERT_GE(scenes.size(), 3u) << "expected the shipped samples in " << source_dir() << "/samples";
    for (const std::string& scene : scenes) {
        SCOPED_TRACE(scene);
        ScratchDir dir;
        const std::string exr = dir.file("exr");
        ProgramResult r = run_program(small_render(scene, {"--exr-dir", exr}));
        SL_EXPECT_EXIT(r, 0);
        EXPECT_TRUE(r.error_lines().empty()) << r.err;
        for (int k = 0; k < 4; ++k) {
            ASSERT_TRUE(fs::exists(exr + "/" + frame_name(k))) << frame_name(k);
            ExrSummary f = summarize_exr(exr + "/" + frame_name(k));
            EXPECT_EQ(f.width, 32);
            EXPECT_EQ(f.height, 32);
            EXPECT_TRUE(f.finite) << frame_name(k) << " has NaN or Inf";
        }
        EXPECT_FALSE(fs::exists(exr + "/" + frame_name(4))) << "more frames than --frames 4";
        ASSERT_TRUE(fs::exists(exr + "/steady.exr"));
        ExrSummary steady = summarize_exr(exr + "/steady.exr");
        EXPECT_EQ(steady.width, 32);
        EXPECT_EQ(steady.height, 32);
        EXPECT_TRUE(steady.finite) << "steady.exr has NaN or Inf";
        EXPECT_GT(steady.mean, 0.0) << "steady.exr is black";
    }
}

// The built-in demo (the Cornell box, constant emission, 0..24 ns): frame 0 covers [0, 2 ns), in
// which light has gone at most 0.6 m from the ceiling light, so the room is still dark apart from
// the emitter itself (which is seen at once and is about 2/3 of the image's mean). The median
// pixel is the room, not the emitter: it must be near zero at first and clearly lit at the end.
TEST(RenderSamples, DefaultDemoStartsDarkAndEndsNearSteady) {
    ScratchDir dir;
    const std::string exr = dir.file("exr");
    const int frames = 12;
    ProgramResult r = run_program(small_render("", {"--exr-dir", exr}, frames, 4, 20000));
    SL_EXPECT_EXIT(r, 0);

    ExrSummary first = summarize_exr(exr + "/" + frame_name(0));
    ExrSummary last = summarize_exr(exr + "/" + frame_name(frames - 1));
    ExrSummary steady = summarize_exr(exr + "/steady.exr");
    ASSERT_GT(last.mean, 0.0);
    const double first_median = median(luminance(first.rgb)), last_median = median(luminance(last.rgb));
    RecordProperty("first_median", std::to_string(first_median));
    RecordProperty("last_median", std::to_string(last_median));
    EXPECT_GT(last_median, 0.0);
    EXPECT_LT(first_median, 0.1 * last_median) << "the room should be dark in the first frame";
    EXPECT_LT(first.mean, 0.8 * last.mean) << "first frame " << first.mean << ", last " << last.mean;

    // By 24 ns light has gone 7.2 m (several bounces); what is still missing is small.
    const double rel = std::abs(last.mean - steady.mean) / steady.mean;
    RecordProperty("last_vs_steady_rel", std::to_string(rel));
    EXPECT_LT(rel, 0.15) << "last frame mean " << last.mean << ", steady " << steady.mean;
    EXPECT_LE(last.mean, steady.mean * (1 + 1e-6)) << "a constant frame cannot exceed the steady state";
}
