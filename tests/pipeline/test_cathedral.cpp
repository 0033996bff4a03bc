// The cathedral sample: its files are what its generator writes, and the real program renders
// it tiny (constant and pulse) with the sun's time origin: dark until the wavefront, which
// enters the scene's bounds at t = 0, can have reached a window or the rose, lit after.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/pipeline/pipeline_helpers.h"

namespace fs = std::filesystem;
using namespace sl::test;

namespace {

std::string cathedral(const std::string& name) { return sample("cathedral/" + name); }

std::string read_all(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST(Cathedral, CommittedFilesAreWhatTheGeneratorWrites) {
    if (std::system("python3 -c 'import json' > /dev/null 2>&1") != 0) GTEST_SKIP() << "no python3";
    ScratchDir dir;
    const std::string out = dir.file("gen");
    const std::string cmd = "python3 '" + cathedral("make_cathedral.py") + "' '" + out + "'";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    for (const char* f : {"nave.obj", "floor.obj", "columns.obj", "cathedral.mtl", "cathedral.json",
                          "cathedral_pulse.json"}) {
        ASSERT_TRUE(fs::exists(cathedral(f))) << f;
        EXPECT_EQ(read_all(out + "/" + f), read_all(cathedral(f))) << f << " differs from the generator's output";
    }
}

// The sun travels along (0.62, -0.5, 0.6); the scene's bounds are x in [-7, 7], y in [0, 20],
// z in [0, 36], so the wavefront starts at the corner (-7, 20, 0). The openings nearest the sun
// are the first window's apex (-7, 12.6, 4.5) and the rose's rim (centre (0, 11, 0), r 2.8):
// nothing inside can be lit before (dot(p, d) - dot(corner, d)) / c = 21.4 ns.
TEST(Cathedral, RendersTinyDarkUntilTheSunlightCanReachAnOpening) {
    const double dn = std::sqrt(0.62 * 0.62 + 0.5 * 0.5 + 0.6 * 0.6);
    auto along = [&](double x, double y, double z) { return (0.62 * x - 0.5 * y + 0.6 * z) / dn; };
    const double h0 = along(-7, 20, 0);
    const double rose = (-0.5 * 11 - 2.8 * std::sqrt(0.62 * 0.62 + 0.5 * 0.5)) / dn;
    const double first_ns = (std::min(along(-7, 12.6, 4.5), rose) - h0) / 0.299792458;
    ASSERT_GT(first_ns, 20.0);
    const int frames = 32;  // 6 ns each over the sample's 0..192 ns
    const double frame_ns = 192.0 / frames;
    for (const char* scene : {"cathedral.json", "cathedral_pulse.json"}) {
        SCOPED_TRACE(scene);
        ScratchDir dir;
        const std::string exr = dir.file("exr");
        ProgramResult r = run_program(small_render(cathedral(scene), {"--exr-dir", exr}, frames, 2, 20000, 48, 27));
        SL_EXPECT_EXIT(r, 0);
        EXPECT_TRUE(r.error_lines().empty()) << r.err;
        double last = 0;
        int lit = 0;
        for (int k = 0; k < frames; ++k) {
            ExrSummary f = summarize_exr(exr + "/" + frame_name(k));
            EXPECT_TRUE(f.finite) << k;
            if ((k + 1) * frame_ns <= first_ns) {
                EXPECT_EQ(f.mean, 0.0) << "frame " << k << " lit before the sun can be in";
            }
            if (std::string(scene) == "cathedral.json") {
                EXPECT_GE(f.mean, last) << "constant sunlight only accumulates: frame " << k;
                last = f.mean;
            }
            lit += f.mean > 0;
        }
        EXPECT_GT(lit, frames / 2) << "the sun should light most frames";
        EXPECT_GT(summarize_exr(exr + "/steady.exr").mean, 0.0);
    }
}
