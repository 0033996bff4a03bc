#include "pipeline/distributed/mpi_launch.h"

#include <dlfcn.h>
#include <unistd.h>

#include <climits>
#include <cstdlib>
#include <filesystem>

namespace sl {
namespace {

using StartFn = RankExchange* (*)(int*, char***, int*, char*, size_t);

}  // namespace

DistributedStart start_distributed(int& argc, char**& argv) {
    DistributedStart s;
    if (launcher_process_count() < 2) return s;
    // Launch mistakes MPI cannot report in one line: every process fails alike, the first prints.
    s.report_error = launcher_process_index() == 0;
    s.error = srun_without_mpi_plugin();
    if (!s.error.empty()) return s;
    // Beside the executable, or on the library path. RTLD_GLOBAL: MPI's own components,
    // loaded by MPI_Init, look for the MPI library's symbols in the global scope.
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    void* lib = nullptr;
    if (n > 0) {
        auto beside = std::filesystem::path(std::string(exe, static_cast<size_t>(n))).parent_path() / "libslowlight_mpi.so";
        if (std::filesystem::exists(beside)) {
            lib = dlopen(beside.c_str(), RTLD_NOW | RTLD_GLOBAL);
        } else {
            lib = dlopen("libslowlight_mpi.so", RTLD_NOW | RTLD_GLOBAL);
        }
    }
    if (!lib) {
        const char* e = dlerror();
        s.error = "started by an MPI launcher, but the MPI plugin libslowlight_mpi.so cannot be loaded: " +
                  std::string(e ? e : "not found");
        return s;
    }
    auto start = reinterpret_cast<StartFn>(dlsym(lib, "slowlight_mpi_start"));
    if (!start) {
        s.error = "the MPI plugin libslowlight_mpi.so has no slowlight_mpi_start";
        return s;
    }
    char why[256] = {};
    int concurrent = 0;
    s.exchange.reset(start(&argc, &argv, &concurrent, why, sizeof why));
    if (!s.exchange) {
        s.error = std::string("cannot start MPI: ") + why;
        return s;
    }
    s.error = rank_count_mismatch(s.exchange->ranks());
    if (!s.error.empty()) {
        s.exchange.reset();  // MPI_Finalize: every process is alone, none waits for another
        return s;
    }
    s.concurrent_channels = concurrent != 0;
    return s;
}

}  // namespace sl
