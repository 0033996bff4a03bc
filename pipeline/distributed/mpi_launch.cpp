#include "pipeline/distributed/mpi_launch.h"

#include <cstdlib>

#include "core/plugin.h"

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
    // RTLD_GLOBAL: MPI's own components, loaded by MPI_Init, look for the MPI library's
    // symbols in the global scope.
    const Plugin plugin = load_plugin("libslowlight_mpi.so", "the MPI plugin", {"slowlight_mpi_start"},
                                      PluginScope::Global);
    if (!plugin.error.empty()) {
        s.error = "started by an MPI launcher, but " + plugin.error;
        return s;
    }
    auto start = plugin.function<StartFn>(0);
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
