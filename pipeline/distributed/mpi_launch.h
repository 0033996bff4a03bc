#pragma once
// Starting MPI only when an MPI launcher started this process with more than one rank: the
// plugin libslowlight_mpi.so (beside the program) is loaded then, and never otherwise, so a
// plain `slowlight render` neither loads nor initialises MPI.
#include <memory>
#include <string>

#include "pipeline/distributed/launch_environment.h"
#include "stages/render/rank_exchange.h"

namespace sl {

struct DistributedStart {
    std::unique_ptr<RankExchange> exchange;  // null: one process, as always
    bool concurrent_channels = false;         // both channels may be busy at once
    std::string error;                        // why MPI could not start, when it should have
    bool report_error = true;                 // this process prints `error` (one of the launched ones does)
};

DistributedStart start_distributed(int& argc, char**& argv);

}  // namespace sl
