#pragma once
// A section's passes when several MPI ranks share the render. Pass k+1's photons (this rank's
// batches, then the all-gather that gives every rank all of them) need no radius and touch only
// the photon batches, so they run while pass k's camera pass reads the grid: the exchange is
// overlapped with work. Then the batches are sorted into the grid with the cell size that the
// ranks agreed on (the largest radius of any rank's pixels); ranks on one machine divide that
// sort among themselves and all-gather the sorted parts. The results are those of one
// process, bit for bit: the same records in the same order, the same radii. Which rank traces
// which batches follows the ranks' measured costs (stages/render/batch_shares.h): a batch's
// records are the same whoever traces it, so only the waiting at the exchange changes.
#include <functional>

#include "stages/render/section_renderer.h"

namespace sl {

void run_passes_on_ranks(const RenderContext& ctx, const SectionLayout& layout, int passes, int64_t photons_per_pass,
                         SectionCounters& counters, SectionBuffer& buffer, PhotonMap& photons, VolumePhotonMap* volume,
                         StageTimes& times, const PassCallback& on_pass, const std::function<bool()>& cancelled);

}  // namespace sl
