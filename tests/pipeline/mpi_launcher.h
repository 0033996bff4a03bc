#pragma once
// Runs the real program under Open MPI's (or MPICH's) mpirun on this machine only: loopback
// and shared memory, as root in CI, more ranks than cores allowed.
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "tests/pipeline/run_program.h"

namespace sl::test {

inline std::string find_mpirun() {
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "/usr/bin");
    std::string d;
    while (std::getline(dirs, d, ':'))
        if (!d.empty() && std::filesystem::exists(std::filesystem::path(d) / "mpirun"))
            return (std::filesystem::path(d) / "mpirun").string();
    return "";
}

// `mpirun [LAUNCHER_ARGS...] -np N slowlight ARGS...`; stdout (rank 0's) to `stdout_path`.
inline ProgramResult run_ranks(int n, const std::vector<std::string>& args, const std::string& stdout_path = "",
                               double timeout_seconds = 120, const std::vector<std::string>& launcher_args = {}) {
    // Open MPI: root allowed (CI runs as root), no network but loopback and shared memory,
    // shared memory without cross-process reads (containers forbid them), oversubscribed.
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    ::setenv("OMPI_MCA_btl", "self,vader", 1);
    ::setenv("OMPI_MCA_btl_vader_single_copy_mechanism", "none", 1);
    ::setenv("OMPI_MCA_rmaps_base_oversubscribe", "1", 1);
    ::setenv("OMPI_MCA_hwloc_base_binding_policy", "none", 1);
    ::setenv("OMPI_MCA_mpi_yield_when_idle", "1", 1);  // more ranks than cores: waiting ones yield
    // One machine: the ob1 layer over shared memory; looking for UCX devices (there are none)
    // costs every rank about 0.3 s of MPI_Init.
    ::setenv("OMPI_MCA_pml", "ob1", 1);
    ::setenv("OMPI_MCA_osc", "^ucx", 1);
    std::vector<std::string> all = launcher_args;
    all.insert(all.end(), {"-np", std::to_string(n), binary()});
    all.insert(all.end(), args.begin(), args.end());
    return run_program(all, stdout_path, timeout_seconds, find_mpirun());
}

}  // namespace sl::test
