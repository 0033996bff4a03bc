#pragma once
// Bad input under MPI: every rank reads the same scene and command line, but some checks (the
// output files) happen on rank 0 only. Before the render starts, the ranks agree: either all
// start, or all stop with the same exit status and one error line, printed by rank 0.
#include <string>

#include "stages/render/rank_exchange.h"

namespace sl {

// `status`: 0 when this rank is ready, else its exit status and `error` its message. Returns 0
// when every rank is ready, else the largest status; rank 0 then prints the error of the
// lowest failing rank as one `error:` line.
int agree_to_start(RankExchange& ex, int status, const std::string& error);

}  // namespace sl
