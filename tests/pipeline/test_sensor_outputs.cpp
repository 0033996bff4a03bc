// The sensor images (--phasor, --gate, --first-arrival) against closed forms, on a point light
// over a plane seen by the camera with its time of flight: direct light only (max_depth 1), so
// the light a pixel receives arrives at t(p) = (|p - light| + |p - camera|) / c for the points p
// the pixel's jittered samples see. Over a pixel, t varies by a few picoseconds; bins are 1 ns.
// Where all of a pixel's samples fall in one bin k (most pixels), the closed forms are exact:
//   amplitude = steady · sinc(fΔ), phase = 2πf·t_k (t_k the bin's centre, within πfΔ of 2πf·t),
//   gate = steady · |bin k ∩ window| / Δ, first arrival = bin k's start (t - Δ < it <= t).
// Every pixel is also checked against a second path: the same sums made here, in double, from
// the --cube planes of the same run.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "config/parse_scene.h"
#include "core/camera.h"
#include "foundation/constants.h"
#include "pipeline/resume_command.h"
#include "stages/output/npy_cube.h"
#include "tests/pipeline/pipeline_helpers.h"

namespace sl::test {
namespace {

constexpr int kRes = 32;
constexpr double kDelta = 1.0;  // ns: 30 frames over [0, 30)
const Vec3 kLight{0.2f, 0.1f, 1.0f};

const char* kScene = R"({
  "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 30, "width": 32, "height": 32},
  "materials": {"grey": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
  "shapes": [{"type": "quad", "corner": [-5, -5, 0], "edge1": [10, 0, 0], "edge2": [0, 10, 0], "material": "grey"}],
  "lights": [{"type": "point", "position": [0.2, 0.1, 1.0], "power": [100, 60, 30]}],
  "time": {"start_ns": 0, "end_ns": 30, "frames": 30},
  "render": {"passes": 4, "photons_per_pass": 1000, "max_depth": 1, "camera_tof": true}
})";

double sinc(double x) { return x == 0 ? 1 : std::sin(kPiDouble * x) / (kPiDouble * x); }

// The phase difference a - b wrapped into (-π, π].
double phase_gap(double a, double b) {
    double d = std::fmod(a - b, 2 * kPiDouble);
    if (d > kPiDouble) d -= 2 * kPiDouble;
    if (d <= -kPiDouble) d += 2 * kPiDouble;
    return d;
}

struct PixelTimes {
    double lo = 1e300, hi = -1e300;  // ns, over the pixel's area (a 7 x 7 grid with its edges)
};

PixelTimes pixel_times(const PinholeCamera& cam, int px, int py) {
    PixelTimes t;
    for (int i = 0; i < 7; ++i)
        for (int j = 0; j < 7; ++j) {
            const Vec3 d = cam.direction(px + i / 6.0f, py + j / 6.0f);
            const Vec3 p = cam.position() + d * (-cam.position().z / d.z);  // on the plane z = 0
            const double v = (length(p - kLight) + length(p - cam.position())) / kSpeedOfLight;
            t.lo = std::min(t.lo, v);
            t.hi = std::max(t.hi, v);
        }
    t.lo -= 1e-3;  // the grid's own resolution, generously
    t.hi += 1e-3;
    return t;
}

class SensorOutputs : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = new ScratchDir("sl_sensor");
        scene_ = dir_->file("plane.json");
        std::ofstream(scene_) << kScene;
        result_ = new ProgramResult(run_program({"render", scene_, "--no-progress", "--exr-dir", dir_->file("exr"),
                                                 "--cube", dir_->file("cube.npy"), "--phasor", "30MHz,400MHz",
                                                 "--gate", "12.75:1.5", "--first-arrival"}));
    }
    static void TearDownTestSuite() {
        delete result_;
        delete dir_;
    }
    static std::string exr(const std::string& name) { return dir_->file("exr") + "/" + name; }

    static ScratchDir* dir_;
    static std::string scene_;
    static ProgramResult* result_;
};
ScratchDir* SensorOutputs::dir_ = nullptr;
std::string SensorOutputs::scene_;
ProgramResult* SensorOutputs::result_ = nullptr;

TEST_F(SensorOutputs, PhasorIsTheSteadyImageTurnedByThePathLength) {
    ASSERT_EQ(result_->exit_code, 0) << result_->err;
    const PinholeCamera cam(parse_scene_file(scene_).camera);
    const ExrImage steady = read_exr(exr("steady.exr"));
    int single_bin = 0;
    for (double f_mhz : {30.0, 400.0}) {
        const double f_ghz = f_mhz / 1000;  // cycles per ns
        const std::string label = f_mhz == 30 ? "30MHz" : "400MHz";
        const ExrImage amp = read_exr(exr("phasor_" + label + "_amplitude.exr"));
        const ExrImage phase = read_exr(exr("phasor_" + label + "_phase.exr"));
        EXPECT_EQ(amp.metadata.at("slowlight:frequency_hz"), f_mhz == 30 ? "30000000" : "400000000");
        single_bin = 0;
        for (int y = 0; y < kRes; ++y)
            for (int x = 0; x < kRes; ++x) {
                const PixelTimes t = pixel_times(cam, x, y);
                const int k_lo = static_cast<int>(std::floor(t.lo / kDelta)), k_hi = static_cast<int>(std::floor(t.hi / kDelta));
                for (int c = 0; c < 3; ++c) {
                    const size_t i = (size_t(y) * kRes + x) * 3 + c;
                    const double v = steady.rgb[i];
                    ASSERT_GT(v, 0) << "pixel " << x << "," << y << " sees the lit plane";
                    // Whatever the bins: the phase lies between the bin centres of the earliest and latest
                    // path, and within πfΔ of 2πf·t (the closed form, for t anywhere in the pixel).
                    const double p_lo = 2 * kPiDouble * f_ghz * ((k_lo + 0.5) * kDelta);
                    const double p_hi = 2 * kPiDouble * f_ghz * ((k_hi + 0.5) * kDelta);
                    const double gap = phase_gap(phase.rgb[i], p_lo);
                    EXPECT_GE(gap, -1e-4) << label << " pixel " << x << "," << y;
                    EXPECT_LE(gap, p_hi - p_lo + 1e-4) << label << " pixel " << x << "," << y;
                    const double closed = 2 * kPiDouble * f_ghz * 0.5 * (t.lo + t.hi);
                    EXPECT_LE(std::abs(phase_gap(phase.rgb[i], closed)),
                              kPiDouble * f_ghz * kDelta + 2 * kPiDouble * f_ghz * 0.5 * (t.hi - t.lo) + 1e-4);
                    if (k_lo == k_hi) {
                        EXPECT_NEAR(amp.rgb[i], v * sinc(f_ghz * kDelta), 2e-5 * v) << label << " pixel " << x << "," << y;
                        EXPECT_NEAR(phase_gap(phase.rgb[i], p_lo), 0, 1e-5);
                        ++single_bin;
                    } else {  // two bins: less than the whole, more than its projection on either
                        EXPECT_LE(amp.rgb[i], v * sinc(f_ghz * kDelta) * (1 + 2e-5));
                        EXPECT_GE(amp.rgb[i], v * sinc(f_ghz * kDelta) * std::cos(p_hi - p_lo) * (1 - 2e-5));
                    }
                }
            }
    }
    EXPECT_GT(single_bin, kRes * kRes * 3 * 3 / 4) << "most pixels' light falls in one bin";
}

TEST_F(SensorOutputs, GateIntegratesTheLightWithinItsWindow) {
    ASSERT_EQ(result_->exit_code, 0) << result_->err;
    const PinholeCamera cam(parse_scene_file(scene_).camera);
    const ExrImage steady = read_exr(exr("steady.exr")), gate = read_exr(exr("gate.exr"));
    // The window [12.75, 14.25) ns: a quarter of bin 12, bin 13 whole, a quarter of bin 14.
    auto weight = [](int k) { return k == 13 ? 1.0 : (k == 12 || k == 14) ? 0.25 : 0.0; };
    int checked = 0, inside = 0;
    for (int y = 0; y < kRes; ++y)
        for (int x = 0; x < kRes; ++x) {
            const PixelTimes t = pixel_times(cam, x, y);
            const int k_lo = static_cast<int>(std::floor(t.lo)), k_hi = static_cast<int>(std::floor(t.hi));
            for (int c = 0; c < 3; ++c) {
                const size_t i = (size_t(y) * kRes + x) * 3 + c;
                const double lo = std::min(weight(k_lo), weight(k_hi)), hi = std::max(weight(k_lo), weight(k_hi));
                EXPECT_GE(gate.rgb[i], steady.rgb[i] * lo * (1 - 1e-5)) << "pixel " << x << "," << y;
                EXPECT_LE(gate.rgb[i], steady.rgb[i] * hi * (1 + 1e-5)) << "pixel " << x << "," << y;
                ++checked;
                inside += weight(k_lo) == 1.0 && k_lo == k_hi;
            }
        }
    EXPECT_EQ(checked, kRes * kRes * 3);
    EXPECT_GT(inside, 30) << "some pixels' light lies wholly in the window (gate = steady)";
    EXPECT_EQ(gate.metadata.at("slowlight:gate_start_ns"), "12.75");
}

TEST_F(SensorOutputs, FirstArrivalIsTheDistanceOverTheSpeedOfLight) {
    ASSERT_EQ(result_->exit_code, 0) << result_->err;
    const PinholeCamera cam(parse_scene_file(scene_).camera);
    const ExrImage first = read_exr(exr("first_arrival.exr"));
    for (int y = 0; y < kRes; ++y)
        for (int x = 0; x < kRes; ++x) {
            const PixelTimes t = pixel_times(cam, x, y);
            for (int c = 0; c < 3; ++c) {
                const float v = first.rgb[(size_t(y) * kRes + x) * 3 + c];
                // The start of the bin of the earliest sample: after the earliest path's bin starts,
                // no later than the latest path, and on a bin edge.
                EXPECT_GE(v, std::floor(t.lo / kDelta) * kDelta) << "pixel " << x << "," << y;
                EXPECT_LE(v, t.hi) << "pixel " << x << "," << y;
                EXPECT_EQ(v, std::floor(v)) << "a bin's start";
            }
        }
}

// The same sums made here from the cube's planes, in double: every pixel, every image.
TEST_F(SensorOutputs, EveryImageEqualsItsSumOverTheCubesPlanes) {
    ASSERT_EQ(result_->exit_code, 0) << result_->err;
    const NpyCube cube = read_npy_cube(dir_->file("cube.npy"));
    ASSERT_EQ(cube.planes, 32);
    const size_t n = size_t(kRes) * kRes * 3;
    const ExrImage amp = read_exr(exr("phasor_400MHz_amplitude.exr")), phase = read_exr(exr("phasor_400MHz_phase.exr"));
    const ExrImage gate = read_exr(exr("gate.exr")), first = read_exr(exr("first_arrival.exr"));
    const ExrImage steady = read_exr(exr("steady.exr"));
    for (size_t i = 0; i < n; ++i) {
        double re = 0, im = 0, g = 0, total = 0;
        float t_first = std::numeric_limits<float>::infinity();
        for (int k = 0; k < 30; ++k) {
            const double v = cube.plane(k + 1)[i], tc = k + 0.5;
            re += v * std::cos(2 * kPiDouble * 0.4 * tc);
            im += v * std::sin(2 * kPiDouble * 0.4 * tc);
            g += v * std::max(0.0, std::min(k + 1.0, 14.25) - std::max(double(k), 12.75));
            if (v > 0 && std::isinf(t_first)) t_first = static_cast<float>(k);
        }
        for (int k = 0; k < 32; ++k) total += cube.plane(k)[i];
        EXPECT_NEAR(amp.rgb[i], sinc(0.4) * std::hypot(re, im), 1e-5 * total) << i;
        EXPECT_NEAR(phase_gap(phase.rgb[i], std::atan2(im, re)), 0, 1e-5) << i;
        EXPECT_NEAR(gate.rgb[i], g, 1e-5 * total) << i;
        EXPECT_EQ(first.rgb[i], t_first) << i;
        EXPECT_NEAR(steady.rgb[i], total, 1e-5 * total) << i;
    }
}

TEST(SensorOutputsInput, AFrequencyAboveTheBinsNyquistLimitIsWarnedAbout) {
    ScratchDir dir("sl_sensor_warn");
    const std::string scene = dir.file("plane.json");
    std::ofstream(scene) << kScene;
    // Δ = 1 ns: the bins resolve up to 500 MHz.
    ProgramResult r = run_program({"render", scene, "--no-progress", "--passes", "1", "--exr-dir", dir.file("exr"),
                                   "--phasor", "400MHz,0.7GHz"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("warning: --phasor 700MHz: above 1/(2 x frame width) = 500MHz"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("--phasor 400MHz"), std::string::npos) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir.file("exr/phasor_700MHz_phase.exr")));
}

// --resume refuses the outputs that need every section in one run: the command printed after
// Ctrl-C leaves them out, so that it is accepted.
TEST(SensorOutputsInput, TheCommandThatContinuesLeavesOutWhatResumeRefuses) {
    EXPECT_EQ(resume_command({"slowlight", "render", "s.json", "--cube", "c.npy", "--cube-layout", "mitransient",
                              "--hdf5=t.h5", "--phasor", "20MHz", "--gate", "1:2", "--first-arrival",
                              "--first-arrival-threshold", "0.5", "--exr-dir", "e", "--", "--gate"}),
              "slowlight render s.json --exr-dir e --resume -- --gate");
    ScratchDir dir("sl_sensor_resume");
    const std::string scene = dir.file("plane.json");
    std::ofstream(scene) << kScene;
    ProgramResult r = run_program({"render", scene, "--no-progress", "--passes", "1", "--exr-dir", dir.file("exr"),
                                   "--first-arrival", "--hdf5", dir.file("t.h5")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // The continuing command's own arguments are accepted (nothing is left to render: exit 0).
    ProgramResult again = run_program({"render", scene, "--no-progress", "--passes", "1", "--exr-dir", dir.file("exr"),
                                       "--resume"});
    EXPECT_EQ(again.exit_code, 0) << again.err;
}

}  // namespace
}  // namespace sl::test
