#include "stages/render/passes_on_ranks.h"

#include "stages/render/batch_shares.h"

#include <tbb/task_group.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace sl {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

void run_passes_on_ranks(const RenderContext& ctx, const SectionLayout& layout, int passes, int64_t photons_per_pass,
                         SectionCounters& counters, SectionBuffer& buffer, PhotonMap& photons, VolumePhotonMap* volume,
                         StageTimes& times, const PassCallback& on_pass, const std::function<bool()>& cancelled) {
    RankExchange& ex = *ctx.exchange;
    double trace_seconds = 0;  // in the background, beside the camera pass
    std::chrono::steady_clock::time_point trace_end;
    auto trace = [&](int pass) {
        const auto t0 = std::chrono::steady_clock::now();
        photons.trace(ctx, layout, pass, photons_per_pass, counters.photons, volume != nullptr);
        trace_end = std::chrono::steady_clock::now();
        trace_seconds += std::chrono::duration<double>(trace_end - t0).count();
    };
    // One reduction per pass, after it: the largest radius of any rank's pixels (the next
    // grid's cell size; max is exact) and whether any rank was interrupted, so that every rank
    // stops before the same pass. It also carries each rank's timings of the pass (in its own
    // slots, the others' being zero, so the maximum gives every rank all of them), from which
    // all ranks compute the same balanced split of the photon batches for the pass after next
    // (the next one's photons are already traced).
    const int n = ex.ranks(), me = ex.rank();
    const size_t nbatches = static_cast<size_t>((photons_per_pass + PhotonMap::kBatch - 1) / PhotonMap::kBatch);
    std::vector<size_t> shares = even_batch_shares(nbatches, n);
    std::vector<double> v(2 + 2 * static_cast<size_t>(n));
    auto agree = [&](double work_seconds, bool traced) {
        std::fill(v.begin(), v.end(), 0.0);
        v[0] = buffer.max_radius;
        v[1] = cancelled && cancelled() ? 1.0 : 0.0;
        const PhotonMap::OwnTrace& own = photons.own_trace();
        if (traced) {
            v[2 + me] = work_seconds;
            if (own.photons > 0) v[2 + n + me] = own.trace_seconds / static_cast<double>(own.photons);
        }
        ex.max(Channel::Passes, v.data(), static_cast<int>(v.size()));
        buffer.max_radius = v[0];
        if (traced && ctx.lights.has_emission()) {
            shares = rebalanced_batch_shares(shares, photons_per_pass, PhotonMap::kBatch,
                                             std::vector<double>(v.begin() + 2, v.begin() + 2 + n),
                                             std::vector<double>(v.begin() + 2 + n, v.end()));
            photons.set_batch_shares(shares);
        }
        return v[1] == 0;
    };
    // A section resumed from its checkpoint continues with its next pass: the random streams
    // are the pass index's, so the passes are those an uninterrupted render makes.
    const int first = buffer.passes_done;
    if (first >= passes || !agree(0, false)) return;
    trace(first);
    tbb::task_group next;
    for (int pass = first; pass < passes; ++pass) {
        auto t0 = std::chrono::steady_clock::now();
        const auto pass_start = t0;
        photons.finish(ctx, 2 * buffer.max_radius, counters.photons, volume);
        times.grid += seconds_since(t0);
        times.photons += seconds_since(t0);
        if (pass + 1 < passes) next.run([&trace, pass] { trace(pass + 1); });
        CameraPassTimes t = camera_pass(ctx, pass, PassPhotons{photons, volume, photons_per_pass}, buffer,
                                        counters.camera);
        times.camera_paths += t.camera_paths;
        times.gather += t.gather;
        times.volume += t.volume;
        times.volume_cpu += t.volume_cpu;
        const auto camera_end = std::chrono::steady_clock::now();
        next.wait();
        // The rank's busy time in the pass: all of it but the part of the photon exchange (its
        // wait for the other ranks included) that no camera work overlapped. With one thread
        // the exchange runs after the camera pass, and all of it is idle.
        double work = seconds_since(pass_start);
        if (pass + 1 < passes)
            work -= std::clamp(std::chrono::duration<double>(trace_end - camera_end).count(), 0.0,
                               photons.own_trace().exchange_seconds);
        const bool go_on = agree(work, pass + 1 < passes);
        if (on_pass) on_pass(buffer.passes_done);
        if (!go_on) break;  // the next pass's photons, already exchanged, are not used
    }
    times.photons += trace_seconds;
}

}  // namespace sl
