#include "stages/render/passes_on_ranks.h"

#include <tbb/task_group.h>

#include <chrono>

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
    if (passes > 0) trace(0);
    tbb::task_group next;
    for (int pass = 0; pass < passes; ++pass) {
        // An interrupt stops every rank before the same pass (pass k's photons, already
        // exchanged, are simply not used).
        if (ex.max(Channel::Passes, cancelled && cancelled() ? 1 : 0) != 0) break;
        auto t0 = std::chrono::steady_clock::now();
        photons.finish(ctx, 2 * buffer.max_radius, counters.photons, volume);
        times.photons += seconds_since(t0);
        if (pass + 1 < passes) next.run([&trace, pass] { trace(pass + 1); });
        CameraPassTimes t = camera_pass(ctx, pass, PassPhotons{photons, volume, photons_per_pass}, buffer,
                                        counters.camera);
        times.camera += t.trace;
        times.gather += t.gather;
        times.volume += t.volume;
        times.volume_cpu += t.volume_cpu;
        next.wait();
        // The next grid's cells fit the largest radius of any rank's pixels (max is exact).
        buffer.max_radius = ex.max(Channel::Passes, buffer.max_radius);
        if (on_pass) on_pass(buffer.passes_done);
    }
    times.photons += trace_seconds;
}

}  // namespace sl
