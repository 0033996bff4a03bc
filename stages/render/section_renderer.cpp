#include "stages/render/section_renderer.h"

#include <tbb/flow_graph.h>

#include <atomic>
#include <chrono>

#include "stages/render/passes_on_ranks.h"

namespace sl {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

RenderCounts counts_of(const SectionCounters& c) {
    RenderCounts n;
    n.photons = c.photons.photons.load();
    n.photon_rays = c.photons.rays.load();
    n.stored = c.photons.stored.load();
    n.stored_volume = c.photons.stored_volume.load();
    n.camera_rays = c.camera.rays.load();
    n.beam_segments = c.camera.beam_segments.load();
    n.beam_hits = c.camera.beam_hits.load();
    return n;
}

}  // namespace

void RenderCounts::add(const RenderCounts& o) {
    photons += o.photons;
    photon_rays += o.photon_rays;
    stored += o.stored;
    stored_volume += o.stored_volume;
    camera_rays += o.camera_rays;
    beam_segments += o.beam_segments;
    beam_hits += o.beam_hits;
}

std::unique_ptr<SectionBuffer> new_section_buffer(const RenderContext& ctx, const SectionLayout& layout) {
    const RankExchange* ex = ctx.exchange;
    auto b = ex ? std::make_unique<SectionBuffer>(PixelShare{ex->rank(), ex->ranks(), ctx.pixels()}, layout,
                                                  ctx.initial_radius, ctx.has_ambient())
                : std::make_unique<SectionBuffer>(ctx.pixels(), layout, ctx.initial_radius, ctx.has_ambient());
    if (!ctx.gather_radii().radius.empty()) b->set_initial_radii(ctx.gather_radii().radius);
    return b;
}

SectionRun render_section(const RenderContext& ctx, const SectionLayout& layout, int passes,
                          int64_t photons_per_pass, const PassCallback& on_pass, const std::function<bool()>& cancelled,
                          std::unique_ptr<SectionBuffer> resume_from, const std::atomic<bool>* abandon) {
    namespace flow = tbb::flow;
    SectionRun run;
    SectionCounters counters;
    RankExchange* ex = ctx.exchange;
    run.buffer = resume_from ? std::move(resume_from) : new_section_buffer(ctx, layout);
    SectionBuffer& buffer = *run.buffer;
    PhotonMap photons;
    // Volume photons exist only with a medium: a vacuum scene allocates none of it.
    std::unique_ptr<VolumePhotonMap> volume;
    if (ctx.medium) {
        volume = std::make_unique<VolumePhotonMap>();
        if (buffer.passes_done == 0) buffer.volume_radius2 = static_cast<double>(ctx.volume_radius) * ctx.volume_radius;
    }

    if (ex) {  // several ranks: their own loop, which overlaps the photon exchange with work
        run_passes_on_ranks(ctx, layout, passes, photons_per_pass, counters, buffer, photons, volume.get(), run.times,
                            on_pass, cancelled);
        run.photon_map_bytes = photons.bytes() + (volume ? volume->bytes() : 0);
        run.counts = counts_of(counters);
        return run;
    }

    // A graph of serial nodes behind a limiter of one: the passes run as a sequence (the source
    // asks `cancelled` where a pass really starts).
    flow::graph g;
    int next_pass = buffer.passes_done;
    // The source makes its next item ahead of time, so `cancelled` is asked where a pass really
    // starts (with the passes done so far); a pass it refuses does nothing (-1).
    std::atomic<bool> stopped{false};
    flow::input_node<int> source(g, [&](tbb::flow_control& fc) -> int {
        if (next_pass >= passes || stopped.load()) {
            fc.stop();
            return 0;
        }
        return next_pass++;
    });
    flow::limiter_node<int> one_pass_at_a_time(g, 1);
    flow::function_node<int, int> photon(g, flow::serial, [&](int pass) {
        if (stopped.load() || (cancelled && cancelled())) {
            stopped = true;
            return -1;
        }
        auto t0 = std::chrono::steady_clock::now();
        bool whole = photons.build(ctx, layout, pass, photons_per_pass, 2 * buffer.max_radius, counters.photons,
                                   volume.get(), abandon);
        run.times.photons += seconds_since(t0);
        if (!whole) {
            stopped = true;
            return -1;
        }
        return pass;
    });
    flow::function_node<int, flow::continue_msg> camera(g, flow::serial, [&](int pass) {
        if (pass < 0) return flow::continue_msg();
        CameraPassTimes t = camera_pass(ctx, pass, PassPhotons{photons, volume.get(), photons_per_pass}, buffer,
                                        counters.camera);
        run.times.camera_paths += t.camera_paths;
        run.times.gather += t.gather;
        run.times.volume += t.volume;
        run.times.volume_cpu += t.volume_cpu;
        if (on_pass) on_pass(buffer.passes_done);
        return flow::continue_msg();
    });

    flow::make_edge(source, one_pass_at_a_time);
    flow::make_edge(one_pass_at_a_time, photon);
    flow::make_edge(photon, camera);
    flow::make_edge(camera, one_pass_at_a_time.decrementer());
    source.activate();
    g.wait_for_all();
    run.photon_map_bytes = photons.bytes() + (volume ? volume->bytes() : 0);
    run.counts = counts_of(counters);
    return run;
}

}  // namespace sl
