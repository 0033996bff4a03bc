// --time-limit renders as many passes as the budget allows, the same number in every section,
// and says how many; --passes stays the upper bound. --preview leaves a contact sheet.
#include <gtest/gtest.h>

#include <fstream>

#include "checkpoint_helpers.h"

namespace sl {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> limited(const std::string& dir, const std::string& limit, const std::string& passes) {
    return {"render", "--width", "24", "--height", "24", "--frames", "4", "--sections", "2", "--photons", "3000",
            "--passes", passes, "--time-limit", limit, "--exr-dir", dir + "/e", "--stats", dir + "/s.json",
            "--no-progress"};
}

TEST(TimeLimit, StopsEverySectionAtTheSamePassWithinTheBudget) {
    const std::string dir = test::fresh_dir("time_limit");
    test::RunResult r = test::run(limited(dir, "1.5s", "1000000"), dir);
    ASSERT_EQ(r.status, 0) << r.err;
    nlohmann::json s = test::read_json(dir + "/s.json");
    ASSERT_TRUE(s.is_object());
    // The first section fixes the passes every section gets; a later one is cut short only when
    // the run has gone a quarter past the budget (a machine that slowed down), and says so.
    const std::vector<int> per = s["passes_per_section"].get<std::vector<int>>();
    ASSERT_EQ(per.size(), 2u);
    const int n = per[0];
    EXPECT_GE(n, 1);
    EXPECT_LT(n, 1000000) << "the budget, not --passes, ended it";
    EXPECT_GE(per[1], 1);
    EXPECT_LE(per[1], n);
    EXPECT_EQ(s["passes_reached"].get<int>(), per[1]);
    if (per[1] < n) {
        EXPECT_GT(s["wall_seconds"].get<double>(), 1.5) << "cut short although within the budget";
        EXPECT_NE(r.err.find("a later section was cut at " + std::to_string(per[1]) + " passes"), std::string::npos)
            << r.err;
    }
    EXPECT_FALSE(s["interrupted"].get<bool>());
    EXPECT_NE(r.err.find("time limit 1.5s: " + std::to_string(n) + " passes per section"), std::string::npos) << r.err;
    // Frames 0-2 are the first section's, frame 3 the second's (192 frames would share alike).
    for (int k = 0; k < 4; ++k) {
        ExrImage img = read_exr(dir + "/e" + test::frame_name(k));
        EXPECT_EQ(img.metadata.at("slowlight:passes"), std::to_string(k < 3 ? per[0] : per[1])) << "frame " << k;
        EXPECT_EQ(img.metadata.count("slowlight:interrupted"), 0u);
    }
    // Within the budget: the rendering itself took no more than the limit plus a pass or two
    // (what a pass costs is measured in the same run, so the check does not depend on speed).
    const double render = s["stage_seconds"]["camera_paths"].get<double>() +
                          s["stage_seconds"]["photon_passes"].get<double>();
    const double per_pass = render / (per[0] + per[1]);
    EXPECT_LT(render, 1.5 + 3 * per_pass + 1.0);
    fs::remove_all(dir);
}

TEST(TimeLimit, PassesStayTheUpperBound) {
    const std::string dir = test::fresh_dir("time_limit_bound");
    test::RunResult r = test::run(limited(dir, "1h", "3"), dir);
    ASSERT_EQ(r.status, 0) << r.err;
    nlohmann::json s = test::read_json(dir + "/s.json");
    EXPECT_EQ(s["passes_per_section"], nlohmann::json::array({3, 3}));
    EXPECT_NE(r.err.find("time limit 1h00m: 3 passes per section"), std::string::npos) << r.err;
    fs::remove_all(dir);
}

// The PNG's size from its IHDR chunk (bytes 16..23, big-endian).
std::pair<int, int> png_size(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    unsigned char h[24] = {};
    f.read(reinterpret_cast<char*>(h), 24);
    if (std::string(reinterpret_cast<char*>(h + 1), 3) != "PNG") return {0, 0};
    auto be = [&](int o) { return (h[o] << 24) | (h[o + 1] << 16) | (h[o + 2] << 8) | h[o + 3]; };
    return {be(16), be(20)};
}

TEST(Preview, LeavesAContactSheetOfTheSection) {
    const std::string dir = test::fresh_dir("preview");
    test::RunResult r = test::run({"render", "--width", "40", "--height", "30", "--frames", "5", "--passes", "3",
                                   "--photons", "2000", "--preview", dir + "/p.png", "--stats", dir + "/s.json",
                                   "--no-progress"},
                                  dir);
    ASSERT_EQ(r.status, 0) << r.err;
    // 5 frames: 3 columns, 2 rows of 40x30 tiles with 2-pixel gaps.
    EXPECT_EQ(png_size(dir + "/p.png"), std::make_pair(3 * 40 + 2 * 2, 2 * 30 + 2));
    EXPECT_GE(test::read_json(dir + "/s.json")["preview_writes"].get<int>(), 1);
    for (auto& e : fs::directory_iterator(dir)) EXPECT_NE(e.path().filename().string()[0], '.') << "temporary file left";
    fs::remove_all(dir);
}

}  // namespace
}  // namespace sl
