#include "pipeline/distributed/launch_environment.h"

#include <climits>
#include <cstdlib>
#include <string>

namespace sl {
namespace {

bool has(const char* name) {
    const char* v = std::getenv(name);
    return v && *v;
}

// The variable as a whole decimal number of at least `least`, else -1.
int env_int(const char* name, long least) {
    const char* v = std::getenv(name);
    if (!v || !*v) return -1;
    char* end = nullptr;
    long x = std::strtol(v, &end, 10);
    return end && *end == '\0' && x >= least && x < INT_MAX ? static_cast<int>(x) : -1;
}

// SLOWLIGHT_MPI: "0" turns MPI off under a launcher, "1" forces it, anything else leaves it to
// the launcher's variables.
bool mpi_switch(const char* value) {
    const char* v = std::getenv("SLOWLIGHT_MPI");
    return v && std::string(v) == value;
}
bool forced() { return mpi_switch("1"); }

}  // namespace

int launcher_process_count() {
    if (mpi_switch("0")) return 1;
    int n = -1;
    if (n < 0) n = env_int("OMPI_COMM_WORLD_SIZE", 1);  // Open MPI's mpirun / mpiexec
    if (n < 0) n = env_int("PMI_SIZE", 1);              // MPICH's Hydra, srun --mpi=pmi2
    if (n < 0 && std::getenv("PMIX_RANK")) n = env_int("SLURM_STEP_NUM_TASKS", 1);  // srun --mpi=pmix
    if (n < 0 && std::getenv("SLURM_STEP_ID") && std::getenv("SLURM_PROCID")) n = env_int("SLURM_STEP_NUM_TASKS", 1);
    if (forced() && n < 2) n = 2;  // let MPI itself say how many
    return n > 1 ? n : 1;
}

int launcher_process_index() {
    for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK", "SLURM_PROCID"}) {
        int i = env_int(name, 0);
        if (i >= 0) return i;
    }
    return 0;
}

std::string srun_without_mpi_plugin() {
    if (forced() || launcher_process_count() < 2) return "";
    // A task of an srun step (not srun's batch script, which has no step id) ...
    if (!has("SLURM_STEP_ID") || !has("SLURM_PROCID")) return "";
    // ... that no process-management interface reaches: srun's PMIx or PMI-2 plugin, or an MPI
    // launcher (mpirun, Hydra) started inside the step, would have set one of these.
    for (const char* name : {"PMIX_RANK", "PMI_FD", "PMI_SIZE", "PMI_RANK", "OMPI_COMM_WORLD_SIZE"})
        if (has(name)) return "";
    return "srun started " + std::to_string(launcher_process_count()) +
           " tasks without an MPI plugin (as with srun --mpi=none), so they cannot form one MPI job; "
           "start them with srun --mpi=pmix (Open MPI) or --mpi=pmi2 (MPICH), or set SLOWLIGHT_MPI=0 for "
           "separate renders";
}

std::string rank_count_mismatch(int mpi_ranks) {
    if (forced()) return "";
    int announced = launcher_process_count();
    if (announced < 2 || mpi_ranks == announced) return "";
    return "the launcher started " + std::to_string(announced) + " processes but MPI counts " +
           std::to_string(mpi_ranks) +
           (mpi_ranks == 1 ? " (each process started MPI alone)" : "") +
           ": this MPI library cannot talk to the launcher (under srun: --mpi=pmix for Open MPI, --mpi=pmi2 "
           "for MPICH)";
}

}  // namespace sl
