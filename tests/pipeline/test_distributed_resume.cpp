// Checkpoints, --resume, --time-limit and --preview when several MPI ranks render (really
// launched with mpirun): the checkpoint is the one-process file, written by rank 0 from every
// rank's pixels, so an interrupted 2-rank render continues in one process or on 3 ranks and
// ends as the uninterrupted one-process render, bit for bit.
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <fstream>
#include <future>
#include <regex>
#include <sstream>
#include <thread>

#include "stages/output/exr_io.h"
#include "tests/pipeline/mpi_launcher.h"
#include "tests/pipeline/pipeline_helpers.h"

namespace sl::test {
namespace {

std::string bytes_of(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

class DistributedResume : public ::testing::Test {
protected:
    void SetUp() override {
        if (find_mpirun().empty()) GTEST_SKIP() << "no mpirun on the PATH (scripts/setup.sh installs Open MPI)";
    }
    ScratchDir dir{"sl_mpi_resume"};
};

// Pixels that differ between the EXR frames (and steady.exr) of two directories.
size_t differing_values(const std::string& a_dir, const std::string& b_dir, int frames) {
    size_t differ = 0;
    std::vector<std::string> names{"steady.exr"};
    for (int f = 0; f < frames; ++f) names.push_back(frame_name(f));
    for (const std::string& n : names) {
        ExrImage a = read_exr(a_dir + "/" + n), b = read_exr(b_dir + "/" + n);
        EXPECT_EQ(a.rgb.size(), b.rgb.size()) << n;
        for (size_t i = 0; i < std::min(a.rgb.size(), b.rgb.size()); ++i) differ += a.rgb[i] != b.rgb[i];
    }
    return differ;
}

// The mpirun whose command line names `marker`, or 0.
pid_t launcher_process(const std::string& marker) {
    for (const auto& e : std::filesystem::directory_iterator("/proc")) {
        const std::string pid = e.path().filename();
        if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
        const std::string cmd = bytes_of("/proc/" + pid + "/cmdline");
        if (cmd.find(marker) != std::string::npos && cmd.find("mpirun") != std::string::npos)
            return static_cast<pid_t>(std::stol(pid));
    }
    return 0;
}

const std::vector<std::string> kScene = {"--width", "40", "--height", "24", "--frames", "6", "--no-progress"};

std::vector<std::string> render_args(const std::string& scene, const std::string& passes, std::vector<std::string> extra,
                                     const std::string& photons = "20000") {
    std::vector<std::string> a = {"render", sample(scene), "--passes", passes, "--photons", photons};
    a.insert(a.end(), kScene.begin(), kScene.end());
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
}

// Renders in one process, then on 2 ranks interrupted (SIGUSR1 to mpirun, which forwards it to
// every rank: the ranks agree to stop after the same pass) once checkpoint `ckpt` exists, with a
// checkpoint after every pass; then resumes a copy on each of `resume_on` rank counts (1: one
// process) and expects every EXR equal to the uninterrupted one-process render.
void interrupt_then_resume(const ScratchDir& dir, const std::string& scene, const std::string& passes,
                           const std::string& photons, const std::vector<std::string>& extra, const std::string& ckpt,
                           const std::vector<int>& resume_on) {
    auto args = [&](std::vector<std::string> more) {
        more.insert(more.end(), extra.begin(), extra.end());
        return render_args(scene, passes, more, photons);
    };
    ProgramResult one = run_program(args({"--exr-dir", dir.file("one")}));
    ASSERT_EQ(one.exit_code, 0) << one.err;

    const std::string cut = dir.file("cut");
    auto job = std::async(std::launch::async,
                          [&] { return run_ranks(2, args({"--exr-dir", cut, "--checkpoint-every", "0"}), "", 120); });
    pid_t launcher = 0;
    for (int tries = 0; tries < 1200; ++tries) {  // once the checkpoint is there
        std::this_thread::sleep_for(std::chrono::milliseconds(25));
        if (std::filesystem::exists(cut + "/" + ckpt) && (launcher = launcher_process(cut))) break;
    }
    ASSERT_NE(launcher, 0) << "no checkpoint appeared";
    ::kill(launcher, SIGUSR1);
    ProgramResult interrupted = job.get();
    ASSERT_FALSE(interrupted.timed_out) << interrupted.err;
    EXPECT_EQ(interrupted.exit_code, 130) << interrupted.err;
    ASSERT_NE(interrupted.err.find("state saved in"), std::string::npos) << interrupted.err;
    ASSERT_TRUE(std::filesystem::exists(cut + "/" + ckpt));
    // Every rank got the signal; the job says so once (rank 0), as one process would.
    const std::string notice = "slowlight: interrupted: ending the pass";
    size_t first = interrupted.err.find(notice);
    EXPECT_NE(first, std::string::npos) << interrupted.err;
    EXPECT_EQ(interrupted.err.find(notice, first + 1), std::string::npos) << interrupted.err;

    for (int ranks : resume_on) {
        const std::string again = dir.file("again" + std::to_string(ranks));
        std::filesystem::copy(cut, again);
        std::vector<std::string> a = args({"--exr-dir", again, "--resume"});
        ProgramResult r = ranks == 1 ? run_program(a) : run_ranks(ranks, a);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        std::smatch m;
        ASSERT_TRUE(std::regex_search(r.err, m, std::regex("from its checkpoint at pass ([0-9]+)"))) << r.err;
        EXPECT_GT(std::stoi(m[1]), 0);
        EXPECT_LT(std::stoi(m[1]), std::stoi(passes)) << "the interrupt came too late to test anything";
        EXPECT_EQ(differing_values(dir.file("one"), again, 6), 0u) << "resumed on " << ranks << " rank(s)";
        EXPECT_FALSE(std::filesystem::exists(again + "/" + ckpt)) << "a finished render keeps no checkpoint";
    }
}

}  // namespace

// One section, in a medium (the volume radius travels in the file): resumed in one process and
// on 3 ranks.
TEST_F(DistributedResume, InterruptedOnTwoRanksResumesInOneProcessAndOnThreeRanksExactly) {
    interrupt_then_resume(dir, "cornell_haze.json", "40", "5000", {}, "section_0000.ckpt", {1, 3});
}

// Two sections, interrupted in the second: on 3 ranks the first comes back from its EXR files
// (read by rank 0 alone) and the second from its checkpoint.
TEST_F(DistributedResume, InterruptedInTheSecondSectionResumesOnThreeRanksExactly) {
    interrupt_then_resume(dir, "cornell_box.json", "30", "20000", {"--sections", "2"}, "section_0001.ckpt", {3});
}

// Three sections of constant light, the last one lost (its last frame and steady.exr gone, no
// checkpoint): on 2 ranks --resume renders it again from the frame the second section carries
// over, which rank 0 reads back from that section's last EXR and deals out to the ranks.
TEST_F(DistributedResume, LostLastSectionResumesOnTwoRanksFromTheCarriedFrameOnDisk) {
    auto args = [&](const std::string& out, std::vector<std::string> more) {
        more.insert(more.end(), {"--sections", "3", "--exr-dir", out});
        return render_args("cornell_box.json", "6", more, "8000");
    };
    ProgramResult one = run_program(args(dir.file("one"), {}));
    ASSERT_EQ(one.exit_code, 0) << one.err;
    const std::string cut = dir.file("cut");
    std::filesystem::copy(dir.file("one"), cut);
    std::filesystem::remove(cut + "/" + frame_name(5));
    std::filesystem::remove(cut + "/steady.exr");
    ProgramResult r = run_ranks(2, args(cut, {"--resume"}));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("section 3/3"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("section 2/3"), std::string::npos) << "only the lost section is rendered:\n" << r.err;
    EXPECT_EQ(differing_values(dir.file("one"), cut, 6), 0u);
}

// --time-limit on 2 ranks: rank 0's clock decides, every rank stops after the same pass, and
// the frames are those of a one-process render given that many passes.
TEST_F(DistributedResume, TimeLimitOnTwoRanksIsTheOneProcessRenderOfThePassesItReached) {
    ProgramResult limited = run_ranks(
        2, render_args("cornell_box.json", "100000", {"--time-limit", "3", "--exr-dir", dir.file("limited")}));
    ASSERT_EQ(limited.exit_code, 0) << limited.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(limited.err, m, std::regex("time limit [^:]*: ([0-9]+) pass"))) << limited.err;
    const std::string reached = m[1];
    EXPECT_GE(std::stoi(reached), 2) << limited.err;
    ExrImage first = read_exr(dir.file("limited") + "/" + frame_name(0));
    EXPECT_EQ(first.metadata["slowlight:passes"], reached);
    ProgramResult one = run_program(render_args("cornell_box.json", reached, {"--exr-dir", dir.file("one")}));
    ASSERT_EQ(one.exit_code, 0) << one.err;
    EXPECT_EQ(differing_values(dir.file("one"), dir.file("limited"), 6), 0u);
}

// --preview on 2 ranks: rank 0 writes the sheet from every rank's pixels; its last version (the
// section's final state) is the one-process sheet, byte for byte.
TEST_F(DistributedResume, PreviewOnTwoRanksIsTheOneProcessSheet) {
    ProgramResult one = run_program(
        render_args("cornell_box.json", "6", {"--preview", dir.file("one.png"), "--exr-dir", dir.file("one")}));
    ASSERT_EQ(one.exit_code, 0) << one.err;
    ProgramResult two = run_ranks(
        2, render_args("cornell_box.json", "6", {"--preview", dir.file("two.png"), "--exr-dir", dir.file("two")}));
    ASSERT_EQ(two.exit_code, 0) << two.err;
    const std::string a = bytes_of(dir.file("one.png")), b = bytes_of(dir.file("two.png"));
    ASSERT_GT(a.size(), 100u);
    EXPECT_TRUE(a == b) << "the preview sheets differ";
}

}  // namespace sl::test
