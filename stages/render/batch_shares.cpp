#include "stages/render/batch_shares.h"

#include <algorithm>
#include <cmath>

namespace sl {

std::vector<size_t> even_batch_shares(size_t nbatches, int ranks) {
    std::vector<size_t> bounds(static_cast<size_t>(ranks) + 1);
    for (int r = 0; r <= ranks; ++r) bounds[static_cast<size_t>(r)] = nbatches * static_cast<size_t>(r) / static_cast<size_t>(ranks);
    return bounds;
}

int64_t photons_in_share(const std::vector<size_t>& bounds, int r, int64_t photons, int batch) {
    auto start = [&](size_t b) { return std::min<int64_t>(static_cast<int64_t>(b) * batch, photons); };
    return start(bounds[static_cast<size_t>(r) + 1]) - start(bounds[static_cast<size_t>(r)]);
}

std::vector<size_t> rebalanced_batch_shares(const std::vector<size_t>& bounds, int64_t photons, int batch,
                                            const std::vector<double>& work, const std::vector<double>& per_photon,
                                            double gain) {
    const size_t n = bounds.size() - 1, nbatches = bounds.back();
    if (n < 2 || work.size() != n || per_photon.size() != n || photons <= 0) return bounds;
    // A rank that traced nothing has no cost per photon of its own: it is given the others'
    // mean, so that it can get batches back.
    std::vector<double> cost = per_photon;
    double known = 0;
    size_t with_cost = 0;
    for (size_t r = 0; r < n; ++r) {
        if (!(std::isfinite(work[r]) && work[r] > 0 && std::isfinite(cost[r]) && cost[r] >= 0)) return bounds;
        if (cost[r] > 0) {
            known += cost[r];
            ++with_cost;
        }
    }
    if (with_cost == 0) return bounds;
    for (double& c : cost)
        if (c == 0) c = known / static_cast<double>(with_cost);
    // The common busy time T at which the ranks would finish together: rank r gets
    // (T - work[r]) / cost[r] photons more (or fewer), and these add up to zero.
    double weighted = 0, rates = 0;
    for (size_t r = 0; r < n; ++r) {
        weighted += work[r] / cost[r];
        rates += 1 / cost[r];
    }
    const double target = weighted / rates;
    // Cumulative photon counts, cut at the nearest batch boundary (a rank may get none).
    std::vector<size_t> next(n + 1, 0);
    double cumulative = 0;
    for (size_t r = 0; r + 1 < n; ++r) {
        const double share = static_cast<double>(photons_in_share(bounds, static_cast<int>(r), photons, batch)) +
                             gain * (target - work[r]) / cost[r];
        cumulative += std::max(0.0, share);
        const double b = std::round(std::min(cumulative, static_cast<double>(photons)) / batch);
        next[r + 1] = std::clamp(static_cast<size_t>(b), next[r], nbatches);
    }
    next[n] = nbatches;
    return next;
}

}  // namespace sl
