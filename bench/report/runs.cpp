#include "runs.h"

#include <sys/resource.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include "core/rng.h"
#include "core/sampling.h"
#include "stages/render/frame_assembly.h"
#include "stages/render/photon_map.h"
#include "stages/render/section_layout.h"
#include "pipeline/frames_in_memory.h"
#include "pipeline/render_frames.h"
#include "bench/common/random_rays.h"

namespace report {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

void keep_best(RayRate& best, double rays, double wall, double cpu) {
    best.per_wall_s = std::max(best.per_wall_s, rays / wall);
    if (cpu > 0) best.per_cpu_s = std::max(best.per_cpu_s, rays / cpu);
}

}  // namespace

double cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

RunResult render(const sl::RenderContext& ctx, Strategy strategy, int passes, int64_t photons_per_pass,
                 bool keep_frames) {
    RunResult out;
    out.passes = passes;
    out.photons_per_pass = photons_per_pass;
    sl::FramesInMemory sink;
    sink.keep_frames = keep_frames;
    auto t0 = Clock::now();
    const double c0 = cpu_seconds();
    auto ts = t0;
    double cs = c0;
    sink.on_section_written = [&](int) {  // a section's wall and CPU time: its passes and its frames
        out.section_s.push_back(since(ts));
        out.section_cpu_s.push_back(cpu_seconds() - cs);
        ts = Clock::now();
        cs = cpu_seconds();
    };
    const sl::PipelineStats stats = sl::render_frames(ctx, {strategy, 1, passes, photons_per_pass}, sink);
    out.wall_s = since(t0);
    out.cpu_s = cpu_seconds() - c0;
    out.frames = std::move(sink.frames);
    out.steady = std::move(sink.steady);
    out.camera_s = stats.render.camera_paths;
    out.photons_s = stats.render.photons;
    out.gather_s = stats.render.gather;
    out.assembly_s = stats.assembly;
    out.camera_rays = stats.counts.camera_rays;
    out.photon_rays = stats.counts.photon_rays;
    out.photons = stats.counts.photons;
    return out;
}

RayRate bare_embree_rays_per_s(const sl::RenderContext& ctx, size_t rays, int rounds) {
    const size_t per_batch = 4096, batches = std::max<size_t>(1, rays / per_batch);
    RayRate best;
    for (int r = 0; r < rounds; ++r) {
        auto t0 = Clock::now();
        const double c0 = cpu_seconds();
        const uint64_t hits = sl::bench::trace_random_rays(ctx, batches, per_batch, static_cast<uint64_t>(r));
        double secs = since(t0), cpu = cpu_seconds() - c0;
        if (hits == 0) return {};  // nothing to hit: no meaningful ceiling
        keep_best(best, static_cast<double>(batches * per_batch), secs, cpu);
    }
    return best;
}

RayRate photon_pass_rays_per_s(const sl::RenderContext& ctx, int passes, int64_t photons_per_pass, int rounds) {
    sl::SectionLayout layout = sl::make_section(ctx.timeline, ctx.emission, 1, 0);
    sl::PhotonMap map;
    RayRate best;
    int pass = 0;
    for (int r = 0; r < rounds; ++r) {
        sl::PhotonTraceCounters counters;
        auto t0 = Clock::now();
        const double c0 = cpu_seconds();
        for (int i = 0; i < passes; ++i)
            map.build(ctx, layout, pass++, photons_per_pass, ctx.initial_radius, counters);
        double secs = since(t0), cpu = cpu_seconds() - c0;
        keep_best(best, static_cast<double>(counters.rays.load()), secs, cpu);
    }
    return best;
}

double rmse(const Image& a, const Image& b) {
    double s = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        double d = static_cast<double>(a[i]) - b[i];
        s += d * d;
    }
    return std::sqrt(s / static_cast<double>(std::max<size_t>(a.size(), 1)));
}

double mean(const Image& a) {
    double s = 0;
    for (float v : a) s += v;
    return s / static_cast<double>(std::max<size_t>(a.size(), 1));
}

size_t count_non_finite(const Image& a) {
    size_t n = 0;
    for (float v : a) n += !std::isfinite(v);
    return n;
}

}  // namespace report
