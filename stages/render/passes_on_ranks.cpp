#include "stages/render/passes_on_ranks.h"

#include <tbb/task_group.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>

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
    auto trace = [&](int pass) {
        const auto t0 = std::chrono::steady_clock::now();
        photons.trace(ctx, layout, pass, photons_per_pass, counters.photons, volume != nullptr);
        trace_seconds += seconds_since(t0);
    };
    // One reduction per pass, after it: the largest radius of any rank's pixels (the next
    // grid's cell size; max is exact) and whether any rank was interrupted, so that every rank
    // stops before the same pass.
    auto agree = [&] {
        double v[2] = {buffer.max_radius, cancelled && cancelled() ? 1.0 : 0.0};
        ex.max(Channel::Passes, v, 2);
        buffer.max_radius = v[0];
        return v[1] == 0;
    };
    // A section resumed from its checkpoint continues with its next pass: the random streams
    // are the pass index's, so the passes are those an uninterrupted render makes.
    const int first = buffer.passes_done;
    if (first >= passes || !agree()) return;
    trace(first);
    tbb::task_group next;
    for (int pass = first; pass < passes; ++pass) {
        auto t0 = std::chrono::steady_clock::now();
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
        next.wait();
        const bool go_on = agree();
        if (on_pass) on_pass(buffer.passes_done);
        if (!go_on) break;  // the next pass's photons, already exchanged, are not used
    }
    times.photons += trace_seconds;
}

}  // namespace sl
