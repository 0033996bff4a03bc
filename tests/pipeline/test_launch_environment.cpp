// How the program reads its launcher's environment, with the variables Slurm 22.05's srun, its
// batch scripts, Open MPI's mpirun and MPICH's Hydra really set (recorded under each): a task of
// `srun --mpi=pmix` or `--mpi=pmi2` is one of N ranks, a batch script is one process, and
// `srun --mpi=none` (no MPI plugin) or an MPI that cannot talk to the launcher is refused with
// one error line before anything is written, instead of N processes each rendering the whole
// video into the same files.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>

#include "pipeline/distributed/launch_environment.h"
#include "pipeline/distributed/mpi_launch.h"
#include "tests/pipeline/pipeline_helpers.h"
#include "tests/pipeline/run_program.h"

namespace sl::test {
namespace {

using Env = std::map<std::string, std::string>;

// Clears every launcher variable for the test's lifetime, sets the given ones, restores all.
class LauncherEnv {
public:
    explicit LauncherEnv(const std::map<std::string, std::string>& set) {
        for (const char* name : kNames) {
            const char* v = std::getenv(name);
            saved_[name] = v ? std::optional<std::string>(v) : std::nullopt;
            ::unsetenv(name);
        }
        for (const auto& [k, v] : set) ::setenv(k.c_str(), v.c_str(), 1);
    }
    ~LauncherEnv() {
        for (const auto& [k, v] : saved_) {
            if (v) ::setenv(k.c_str(), v->c_str(), 1);
            else ::unsetenv(k.c_str());
        }
    }
    LauncherEnv(const LauncherEnv&) = delete;
    LauncherEnv& operator=(const LauncherEnv&) = delete;

private:
    static constexpr const char* kNames[] = {
        "OMPI_COMM_WORLD_SIZE", "OMPI_COMM_WORLD_RANK", "PMI_SIZE",       "PMI_RANK",     "PMI_FD",
        "PMIX_RANK",            "PMIX_NAMESPACE",       "SLURM_JOB_ID",   "SLURM_STEP_ID", "SLURM_PROCID",
        "SLURM_NTASKS",         "SLURM_STEP_NUM_TASKS", "SLOWLIGHT_MPI"};
    std::map<std::string, std::optional<std::string>> saved_;
};

// A task of `srun -n N` as srun sets it up, before any MPI plugin adds its own variables.
std::map<std::string, std::string> srun_task(int n, int index) {
    return {{"SLURM_JOB_ID", "41"},          {"SLURM_STEP_ID", "0"},
            {"SLURM_PROCID", std::to_string(index)}, {"SLURM_NTASKS", std::to_string(n)},
            {"SLURM_STEP_NUM_TASKS", std::to_string(n)}};
}

std::map<std::string, std::string> with(std::map<std::string, std::string> env,
                                        const std::map<std::string, std::string>& more) {
    for (const auto& [k, v] : more) env[k] = v;
    return env;
}

}  // namespace

TEST(LaunchEnvironment, SrunTasksAreRanksWithEitherMpiPlugin) {
    {
        LauncherEnv env(with(srun_task(2, 1), {{"PMIX_RANK", "1"}, {"PMIX_NAMESPACE", "slurm.pmix.41.0"}}));
        EXPECT_EQ(launcher_process_count(), 2);
        EXPECT_EQ(launcher_process_index(), 1);
        EXPECT_EQ(srun_without_mpi_plugin(), "");
    }
    {
        LauncherEnv env(with(srun_task(3, 2), {{"PMI_FD", "11"}, {"PMI_RANK", "2"}, {"PMI_SIZE", "3"}}));
        EXPECT_EQ(launcher_process_count(), 3);
        EXPECT_EQ(launcher_process_index(), 2);
        EXPECT_EQ(srun_without_mpi_plugin(), "");
    }
}

TEST(LaunchEnvironment, ABatchScriptOrAOneTaskStepIsOneProcess) {
    {
        // sbatch --ntasks=2: the script itself runs once, with no step id.
        LauncherEnv env(Env{{"SLURM_JOB_ID", "41"}, {"SLURM_NTASKS", "2"}, {"SLURM_PROCID", "0"}});
        EXPECT_EQ(launcher_process_count(), 1);
        EXPECT_EQ(srun_without_mpi_plugin(), "");
    }
    {
        LauncherEnv env(srun_task(1, 0));
        EXPECT_EQ(launcher_process_count(), 1);
        EXPECT_EQ(srun_without_mpi_plugin(), "");
    }
}

TEST(LaunchEnvironment, SrunWithoutAnMpiPluginIsNamedAndSlowlightMpiZeroOptsOut) {
    {
        LauncherEnv env(srun_task(2, 0));
        EXPECT_EQ(launcher_process_count(), 2);
        std::string why = srun_without_mpi_plugin();
        EXPECT_NE(why.find("--mpi=pmix"), std::string::npos) << why;
        EXPECT_NE(why.find("2 tasks"), std::string::npos) << why;
    }
    {
        LauncherEnv env(with(srun_task(2, 0), {{"SLOWLIGHT_MPI", "0"}}));
        EXPECT_EQ(launcher_process_count(), 1);
        EXPECT_EQ(srun_without_mpi_plugin(), "");
    }
}

TEST(LaunchEnvironment, MpirunInsideAnSrunStepIsMpirunsJob) {
    // An interactive `srun --pty bash`, then mpirun -np 4: the ranks inherit the step's variables.
    LauncherEnv env(with(srun_task(1, 0), {{"OMPI_COMM_WORLD_SIZE", "4"}, {"OMPI_COMM_WORLD_RANK", "3"},
                                           {"PMIX_RANK", "3"}}));
    EXPECT_EQ(launcher_process_count(), 4);
    EXPECT_EQ(launcher_process_index(), 3);
    EXPECT_EQ(srun_without_mpi_plugin(), "");
}

TEST(LaunchEnvironment, MpiCountingOtherThanTheLauncherIsRefused) {
    {
        LauncherEnv env(with(srun_task(3, 0), {{"PMIX_RANK", "0"}}));
        EXPECT_EQ(rank_count_mismatch(3), "");
        EXPECT_NE(rank_count_mismatch(1).find("started 3 processes but MPI counts 1"), std::string::npos);
        EXPECT_NE(rank_count_mismatch(2), "");
    }
    {
        LauncherEnv env(Env{{"SLOWLIGHT_MPI", "1"}});  // forced: MPI's own count is the count
        EXPECT_EQ(rank_count_mismatch(1), "");
    }
}

// The whole program, started as srun --mpi=none would start its first and second task.
TEST(LaunchUnderSlurm, SrunWithoutAnMpiPluginEndsWithOneErrorLineAndWritesNothing) {
    ScratchDir dir{"sl_srun_none"};
    const std::vector<std::string> args = {"render",   "--width", "16",    "--height", "16",
                                           "--frames", "2",       "--passes", "1",     "--photons",
                                           "1000",     "--no-progress", "--exr-dir", dir.file("exr"),
                                           "-o",       dir.file("out.mp4")};
    ProgramResult first, second;
    {
        LauncherEnv env(with(srun_task(2, 0), {{"LD_DEBUG", "files"}}));
        first = run_program(args);
        ::unsetenv("LD_DEBUG");
    }
    {
        LauncherEnv env(srun_task(2, 1));
        second = run_program(args);
    }
    EXPECT_EQ(first.exit_code, 1) << first.err;
    ASSERT_EQ(first.error_lines().size(), 1u) << first.err;
    EXPECT_NE(first.error_lines()[0].find("--mpi=pmix"), std::string::npos) << first.err;
    EXPECT_EQ(first.err.find("libmpi"), std::string::npos) << "MPI was loaded";
    EXPECT_EQ(second.exit_code, 1) << second.err;
    EXPECT_TRUE(second.error_lines().empty()) << second.err;  // one line for the job
    EXPECT_FALSE(std::filesystem::exists(dir.file("out.mp4")));
    EXPECT_FALSE(std::filesystem::exists(dir.file("exr")));
}

TEST(LaunchUnderSlurm, APlainRenderInABatchScriptIsOneProcess) {
    ScratchDir dir{"sl_sbatch"};
    LauncherEnv env(Env{{"SLURM_JOB_ID", "41"}, {"SLURM_NTASKS", "2"}, {"SLURM_PROCID", "0"}});
    ProgramResult r = run_program({"render", "--width", "16", "--height", "16", "--frames", "2", "--passes", "1",
                                   "--photons", "1000", "--no-progress", "-o", dir.file("out.mp4")});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.find("MPI ranks"), std::string::npos) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir.file("out.mp4")));
}

// A launcher announces 2 processes that MPI cannot join (here: Hydra's variables without Hydra,
// so MPI starts this process alone): refused, instead of two whole renders into the same files.
TEST(LaunchUnderSlurm, ProcessesThatStartMpiAloneAreRefused) {
    if (!std::filesystem::exists(std::filesystem::path(binary()).parent_path() / "libslowlight_mpi.so"))
        GTEST_SKIP() << "built without MPI";
    ScratchDir dir{"sl_mpi_alone"};
    LauncherEnv env(Env{{"PMI_SIZE", "2"}, {"PMI_RANK", "0"}});
    ProgramResult r = run_program({"render", "--width", "16", "--height", "16", "--frames", "2", "--passes", "1",
                                   "--photons", "1000", "--no-progress", "-o", dir.file("out.mp4")});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    ASSERT_EQ(r.error_lines().size(), 1u) << r.err;
    EXPECT_NE(r.error_lines()[0].find("MPI counts 1"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out.mp4")));
}

}  // namespace sl::test
