#pragma once
// What the launcher's environment says about this process, read before MPI is touched: how many
// processes it started, which one this is, and whether they were started in a way no MPI library
// can join into one job (Slurm's `srun --mpi=none`: the tasks get no process-management interface,
// so each would start MPI alone and render, and write, the whole video by itself).
#include <string>

namespace sl {

// The number of processes the launcher's environment announces (Open MPI's mpirun, MPICH's
// Hydra, Slurm's srun with PMI-2 or PMIx), or 1. SLOWLIGHT_MPI=0 turns MPI off, =1 forces it.
int launcher_process_count();

// This process's index among those launcher_process_count() announces (the launcher's variable;
// 0 when none says).
int launcher_process_index();

// Non-empty when srun started several tasks without an MPI plugin: the reason, for an error line.
std::string srun_without_mpi_plugin();

// Non-empty when MPI, once started, counts `mpi_ranks` processes where the launcher announced
// another number (an MPI library that cannot talk to this launcher starts every process alone).
std::string rank_count_mismatch(int mpi_ranks);

}  // namespace sl
