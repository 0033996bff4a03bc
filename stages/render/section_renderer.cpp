#include "stages/render/section_renderer.h"

#include <tbb/flow_graph.h>

#include <chrono>
#include <ctime>

#include "stages/render/gather.h"

namespace sl {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

SectionRun render_section(const RenderContext& ctx, const SectionLayout& layout, int passes,
                          int64_t photons_per_pass, SectionCounters& counters,
                          const PassCallback& on_pass, const std::function<bool()>& cancelled) {
    namespace flow = tbb::flow;
    SectionRun run;
    run.buffer = std::make_unique<SectionBuffer>(ctx.pixels(), layout, ctx.initial_radius, ctx.has_ambient());
    SectionBuffer& buffer = *run.buffer;
    VisiblePoints vps;
    PhotonMap photons;
    // Volume state exists only with a medium: a vacuum scene allocates none of it.
    std::unique_ptr<CameraSegments> segments;
    std::unique_ptr<VolumePhotonMap> volume;
    if (ctx.medium) {
        segments = std::make_unique<CameraSegments>();
        volume = std::make_unique<VolumePhotonMap>();
        buffer.volume_radius2 = static_cast<double>(ctx.volume_radius) * ctx.volume_radius;
    }

    flow::graph g;
    int next_pass = 0;
    flow::input_node<int> source(g, [&](tbb::flow_control& fc) -> int {
        if (next_pass >= passes || (cancelled && cancelled())) {
            fc.stop();
            return 0;
        }
        return next_pass++;
    });
    flow::limiter_node<int> one_pass_at_a_time(g, 1);
    flow::function_node<int, int> camera(g, flow::serial, [&](int pass) {
        auto t0 = std::chrono::steady_clock::now();
        camera_pass(ctx, pass, vps, buffer, counters.camera, segments.get());
        run.times.camera += seconds_since(t0);
        return pass;
    });
    flow::function_node<int, int> photon(g, flow::serial, [&](int pass) {
        auto t0 = std::chrono::steady_clock::now();
        photons.build(ctx, layout, pass, photons_per_pass, 2 * buffer.max_radius, counters.photons, volume.get());
        run.times.photons += seconds_since(t0);
        return pass;
    });
    flow::join_node<std::tuple<int, int>, flow::queueing> both(g);
    flow::function_node<std::tuple<int, int>, flow::continue_msg> gather(
        g, flow::serial, [&](const std::tuple<int, int>&) {
            auto t0 = std::chrono::steady_clock::now();
            if (volume) {
                const std::clock_t c0 = std::clock();
                BeamCounters c = gather_volume(ctx, *segments, *volume, photons_per_pass, buffer);
                run.times.volume_cpu += static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
                counters.beam_segments.fetch_add(c.segments, std::memory_order_relaxed);
                counters.beam_hits.fetch_add(c.photon_hits, std::memory_order_relaxed);
                run.times.volume += seconds_since(t0);
            }
            gather_photons(ctx, vps, photons, photons_per_pass, buffer);
            run.times.gather += seconds_since(t0);
            if (on_pass) on_pass(buffer.passes_done);
            return flow::continue_msg();
        });

    flow::make_edge(source, one_pass_at_a_time);
    flow::make_edge(one_pass_at_a_time, camera);
    flow::make_edge(one_pass_at_a_time, photon);
    flow::make_edge(camera, flow::input_port<0>(both));
    flow::make_edge(photon, flow::input_port<1>(both));
    flow::make_edge(both, gather);
    flow::make_edge(gather, one_pass_at_a_time.decrementer());
    source.activate();
    g.wait_for_all();
    run.photon_map_bytes = photons.bytes() + (volume ? volume->bytes() + segments->bytes() : 0);
    return run;
}

}  // namespace sl
