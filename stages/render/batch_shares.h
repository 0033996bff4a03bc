#pragma once
// Which photon batches each MPI rank traces, balanced by what the ranks' work costs rather than
// by count. Every pass ends with all ranks waiting for the slowest at the photon exchange, so a
// rank that is slower (more photons: 200,000 photons are 195 batches of 1024 and one of 320; a
// core shared with another process; more expensive pixels) makes every other rank idle. Each
// batch keeps its own random stream and its place in the map whoever traces it, so any split
// gives the same photon map, bit for bit: only the waiting changes.
//
// A split is the ranks' contiguous shares of the batches, as boundaries: rank r traces batches
// [bounds[r], bounds[r + 1]), bounds[0] = 0 and bounds[ranks] = the batch count.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sl {

// Equal counts of batches (the split before anything was measured).
std::vector<size_t> even_batch_shares(size_t nbatches, int ranks);

// Photon paths in rank r's share: batches hold `batch` photons, the last one what is left.
int64_t photons_in_share(const std::vector<size_t>& bounds, int r, int64_t photons, int batch);

// The next pass's split, from the pass just measured with split `bounds`: `work[r]` is rank r's
// busy time in that pass (sort, camera pass, tracing; not the time it waited for other ranks)
// and `per_photon[r]` its tracing time per photon path. Each rank's share moves by `gain` of
// the photons that would make all ranks' busy times equal if a photon cost per_photon[r] on
// rank r (gain < 1 damps the noise of one pass's timings). Identical inputs give identical
// outputs, so every rank computes the same split. A rank that traced nothing (per_photon 0) is
// priced at the other ranks' mean; other unusable timings (work not positive, not finite) keep
// `bounds`.
std::vector<size_t> rebalanced_batch_shares(const std::vector<size_t>& bounds, int64_t photons, int batch,
                                            const std::vector<double>& work, const std::vector<double>& per_photon,
                                            double gain = 0.5);

}  // namespace sl
