// One render on several MPI ranks (really launched with mpirun, on this machine): it must be
// the single-process render exactly, bit for bit, and it must end cleanly when a rank dies or
// the input is bad. Images are tiny and passes few: each launch takes a second or two.
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <fstream>
#include <future>
#include <thread>

#include "tests/common/video_reader.h"
#include "tests/pipeline/mpi_launcher.h"
#include "tests/pipeline/pipeline_helpers.h"

namespace sl::test {
namespace {

std::string file_bytes(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

class Distributed : public ::testing::Test {
protected:
    void SetUp() override {
        if (find_mpirun().empty()) GTEST_SKIP() << "no mpirun on the PATH (scripts/setup.sh installs Open MPI)";
    }
    ScratchDir dir{"sl_mpi"};
};

// Renders `args` in one process and on `ranks` ranks, with EXR frames, the cube, the HDF5 file,
// the sensor images and a video on stdout (YUV4MPEG2: the decoded pictures themselves), and expects every output equal.
void expect_same_render(const ScratchDir& dir, const std::vector<std::string>& args, std::vector<int> rank_counts,
                        const std::vector<std::string>& launcher_args = {}) {
    auto outputs = [&](const std::string& tag) {
        std::vector<std::string> a = args;
        a.insert(a.end(), {"--no-progress", "--exr-dir", dir.file(tag), "--cube", dir.file(tag + ".npy"), "-o", "-"});
        // The files other tools read and the sensor images (in --exr-dir, compared with the frames).
        a.insert(a.end(), {"--hdf5", dir.file(tag + ".h5"), "--phasor", "20MHz,300MHz", "--first-arrival"});
        return a;
    };
    ProgramResult one = run_program(outputs("one"), dir.file("one.y4m"));
    ASSERT_EQ(one.exit_code, 0) << one.err;
    const std::string video = file_bytes(dir.file("one.y4m"));
    ASSERT_GT(video.size(), 1000u);
    std::vector<std::string> exrs;
    for (const auto& e : std::filesystem::directory_iterator(dir.file("one"))) exrs.push_back(e.path().filename());
    ASSERT_GE(exrs.size(), 3u);  // frames and steady.exr
    for (int n : rank_counts) {
        const std::string tag = "ranks" + std::to_string(n);
        ProgramResult many = run_ranks(n, outputs(tag), dir.file(tag + ".y4m"), 120, launcher_args);
        ASSERT_EQ(many.exit_code, 0) << many.err;
        EXPECT_NE(many.err.find(std::to_string(n) + " MPI ranks"), std::string::npos) << many.err;
        for (const std::string& name : exrs) {
            ExrImage a = read_exr(dir.file("one") + "/" + name), b = read_exr(dir.file(tag) + "/" + name);
            ASSERT_EQ(a.rgb.size(), b.rgb.size()) << name;
            size_t differ = 0;
            for (size_t i = 0; i < a.rgb.size(); ++i) differ += a.rgb[i] != b.rgb[i];
            EXPECT_EQ(differ, 0u) << name << " on " << n << " ranks: values differ from one process";
        }
        // On a mismatch, the sizes and the first differing byte say whether a file was cut short
        // or its values differ (and stderr, whether a rank said anything).
        auto same = [&](const std::string& a, const std::string& b, const char* what) {
            if (a == b) return;
            size_t at = 0;
            while (at < std::min(a.size(), b.size()) && a[at] == b[at]) ++at;
            ADD_FAILURE() << what << ", " << n << " ranks: " << a.size() << " bytes in one process, " << b.size()
                          << " on ranks, first difference at byte " << at << "\n" << many.err;
        };
        same(file_bytes(dir.file("one.npy")), file_bytes(dir.file(tag + ".npy")), "cube");
        same(file_bytes(dir.file("one.h5")), file_bytes(dir.file(tag + ".h5")), "HDF5 file");
        same(video, file_bytes(dir.file(tag + ".y4m")), "decoded video");
    }
}

const std::vector<std::string> kSmall = {"--width", "40", "--height", "24", "--frames", "6", "--passes", "4",
                                         "--photons", "20000"};

std::vector<std::string> with(const std::string& scene, std::vector<std::string> extra) {
    std::vector<std::string> a = {"render", sample(scene)};
    a.insert(a.end(), kSmall.begin(), kSmall.end());
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
}

}  // namespace

TEST_F(Distributed, ConstantEmissionOnTwoAndThreeRanksIsTheOneProcessRender) {
    expect_same_render(dir, with("cornell_box.json", {}), {2, 3});
}

// Pulses, a medium (its volume photons travel with the surface ones), glass, K sections (the
// exposure then comes from a preview) and the camera's time of flight, all at once.
TEST_F(Distributed, PulseInAMediumWithSectionsAndCameraTofIsTheOneProcessRender) {
    expect_same_render(dir, with("cornell_haze_glass_pulse.json", {"--sections", "2", "--camera-tof"}), {3});
}

TEST_F(Distributed, ConstantEmissionWithSectionsAndAMediumIsTheOneProcessRender) {
    expect_same_render(dir, with("cornell_haze.json", {"--sections", "3"}), {2});
}

// Started from an Open MPI hostfile, as on a cluster (here the one host, two slots, two ranks
// mapped onto it): the same render. MPICH's Hydra reads other options, so only under Open MPI.
TEST_F(Distributed, AHostfileLaunchIsTheOneProcessRender) {
    run_program({"--version"}, dir.file("launcher_version"), 30, find_mpirun());
    if (file_bytes(dir.file("launcher_version")).find("Open MPI") == std::string::npos)
        GTEST_SKIP() << "the hostfile options here are Open MPI's";
    {
        std::ofstream hosts(dir.file("hosts"));
        hosts << "localhost slots=2\n";
    }
    expect_same_render(dir, with("cornell_box.json", {"--sections", "2"}), {2},
                       {"--hostfile", dir.file("hosts"), "--map-by", "ppr:2:node"});
}

// Ranks on separate machines each sort the whole photon map (on one machine they divide the
// sort and gather the sorted parts): that path too is the one-process render, bit for bit.
TEST_F(Distributed, RanksOnSeparateMachinesSortingTheWholeMapAreTheOneProcessRender) {
    struct ApartWhileInScope {  // unset again however the test ends: later tests divide the sort
        ApartWhileInScope() { ::setenv("SLOWLIGHT_RANKS_AS_NODES", "1", 1); }
        ~ApartWhileInScope() { ::unsetenv("SLOWLIGHT_RANKS_AS_NODES"); }
    } apart;
    expect_same_render(dir, with("cornell_haze.json", {"--sections", "2"}), {2});
}

// A rank killed (SIGKILL) in the middle of the passes: the job ends, soon, with an error line
// and a non-zero status, and no frame of the unfinished section is written.
TEST_F(Distributed, ARankKilledMidRenderEndsTheJobWithAnError) {
    const std::string marker = dir.file("killed");
    std::vector<std::string> args = {"render", sample("cornell_box.json"), "--width", "48", "--height", "32",
                                     "--frames", "4", "--passes", "100000", "--photons", "20000", "--no-progress",
                                     "--exr-dir", marker, "--checkpoint-every", "0"};
    auto job = std::async(std::launch::async, [&] { return run_ranks(3, args, "", 90); });
    // The event that the ranks render: rank 0 saved the first pass's checkpoint (not CPU time,
    // which a rank spinning in MPI's start-up collective also burns on a loaded machine).
    const std::string first_pass = marker + "/section_0000.ckpt";
    for (int tries = 0; tries < 6000 && !std::filesystem::exists(first_pass); ++tries)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_TRUE(std::filesystem::exists(first_pass)) << "the ranks never finished a pass";
    // Rank 1, found by its environment and this test's own output path.
    pid_t victim = 0;
    for (const auto& e : std::filesystem::directory_iterator("/proc")) {
        const std::string pid = e.path().filename();
        if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
        const std::string cmd = file_bytes("/proc/" + pid + "/cmdline"), env = file_bytes("/proc/" + pid + "/environ");
        if (cmd.find(marker) == std::string::npos || cmd.find("mpirun") != std::string::npos) continue;
        if (env.find(std::string("OMPI_COMM_WORLD_RANK=1") + '\0') != std::string::npos ||
            env.find(std::string("PMI_RANK=1") + '\0') != std::string::npos)
            victim = static_cast<pid_t>(std::stol(pid));
    }
    ASSERT_NE(victim, 0) << "rank 1 never got to rendering";
    ASSERT_EQ(::kill(victim, SIGKILL), 0);
    ProgramResult r = job.get();
    EXPECT_FALSE(r.timed_out) << "the job hung after a rank died:\n" << r.err;
    EXPECT_NE(r.exit_code, 0) << r.err;
    // Our line is written by rank 0's handler of the launcher's SIGTERM. Open MPI's mpirun may end
    // the job before it forwards a rank's last line (seen once in about 80 runs on a loaded
    // machine, with the job's status right); its own report of the killed rank then stands.
    const bool reported = !r.error_lines().empty() || r.err.find("exited on signal 9") != std::string::npos;
    EXPECT_TRUE(reported) << r.err;
    EXPECT_FALSE(std::filesystem::exists(marker + "/" + frame_name(0))) << "an unfinished frame was written";
}

// Bad input: one error line (rank 0's), exit status 2 from every rank, so from mpirun too.
TEST_F(Distributed, BadInputIsReportedOnceWithStatusTwo) {
    ProgramResult missing = run_ranks(3, {"render", dir.file("no_such_scene.json"), "--no-progress"});
    EXPECT_EQ(missing.exit_code, 2) << missing.err;
    ASSERT_EQ(missing.error_lines().size(), 1u) << missing.err;
    EXPECT_NE(missing.error_lines()[0].find("no_such_scene.json"), std::string::npos);

    // Checked by rank 0 alone (only it writes): the others must stop with it, not wait.
    ProgramResult container = run_ranks(2, with("cornell_box.json", {"-o", dir.file("video.xyz")}));
    EXPECT_EQ(container.exit_code, 2) << container.err;
    ASSERT_EQ(container.error_lines().size(), 1u) << container.err;
    EXPECT_NE(container.error_lines()[0].find(".xyz"), std::string::npos);

    ProgramResult ranks = run_ranks(2, with("cornell_box.json", {"--ranks", "3"}));
    EXPECT_EQ(ranks.exit_code, 2) << ranks.err;
    EXPECT_EQ(ranks.error_lines().size(), 1u) << ranks.err;
}

}  // namespace sl::test

namespace sl::test {

// Without a launcher, a render never loads MPI: the dynamic loader's own list of the libraries
// it opened (LD_DEBUG=files) names TBB, and no MPI library or plugin.
TEST(PlainRun, NeverLoadsMpi) {
    ScratchDir dir{"sl_plain"};
    ::setenv("LD_DEBUG", "files", 1);
    ProgramResult r = run_program({"render", "--width", "16", "--height", "16", "--frames", "2", "--passes", "1",
                                   "--photons", "1000", "--no-progress", "--exr-dir", dir.file("exr")});
    ::unsetenv("LD_DEBUG");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_NE(r.err.find("libtbb"), std::string::npos) << "the loader listed nothing:\n" << r.err.substr(0, 2000);
    EXPECT_EQ(r.err.find("libmpi"), std::string::npos);
    EXPECT_EQ(r.err.find("libslowlight_mpi"), std::string::npos);
}

}  // namespace sl::test
