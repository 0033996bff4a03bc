// Single convergence against the number of frames, and the photon pass against bare Embree.
//
//   ./build/bench_frames [--passes N] [--photons N] [--rounds N]   (Cornell box, 256x256)
//
// Prints, in one run: render time for F = 1, 8, 48, 192 frames (one convergence each, frame
// assembly included) with the ratio to F = 1, wall and process CPU time (best of the rounds), and photon-pass rays per second against bare
// Embree rays per second (random rays in the same scene, same threads).
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>

#include "config/parse_scene.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "pipeline/frames_in_memory.h"
#include "pipeline/render_frames.h"
#include "stages/render/render_context.h"
#include "bench/common/random_rays.h"

namespace {

using Clock = std::chrono::steady_clock;
int g_passes = 16, g_rounds = 3;
long long g_photons = 100000;
std::map<int, double> g_best_seconds;   // F -> fastest whole render
std::map<int, double> g_best_cpu;       // F -> least process CPU time (user + system) of a render

// CPU seconds of the whole process (every thread, user and system). On a machine shared with
// other work a render's wall time also counts the time it waited for a core; its CPU time does
// not, so the CPU ratio stays readable when the wall ratio is noise.
double process_cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    auto s = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
    return s(u.ru_utime) + s(u.ru_stime);
}
double g_photon_rays_per_s = 0, g_bare_rays_per_s = 0, g_camera_rays_per_s = 0;
double g_photon_trace_rays_per_s = 0;  // the photon pass without its grid sort

sl::SceneDesc cornell(int frames) {
    sl::SceneDesc s = sl::parse_scene_file(std::string(SLOWLIGHT_SOURCE_DIR) + "/samples/cornell_box.json");
    s.camera.width = s.camera.height = 256;
    s.time.frames = frames;
    s.render.passes = g_passes;
    s.render.photons_per_pass = g_photons;
    return s;
}

void BM_Render(benchmark::State& state) {
    const int frames = static_cast<int>(state.range(0));
    sl::SceneDesc scene = cornell(frames);
    sl::RenderContext ctx(scene);
    for (auto _ : state) {
        const double cpu0 = process_cpu_seconds();
        auto t0 = Clock::now();
        sl::FramesInMemory sink;
        sink.keep_frames = false;  // assembled and timed, not kept
        const sl::PipelineStats stats = sl::render_frames(ctx, {}, sink);
        state.counters["assemble_s"] = stats.assembly;
        state.counters["buffer_s"] = stats.buffers;
        double secs = std::chrono::duration<double>(Clock::now() - t0).count();
        state.SetIterationTime(secs);
        auto& best = g_best_seconds[frames];
        best = best == 0 ? secs : std::min(best, secs);
        const double cpu = process_cpu_seconds() - cpu0;
        auto& best_cpu = g_best_cpu[frames];
        best_cpu = best_cpu == 0 ? cpu : std::min(best_cpu, cpu);
        state.counters["photon_pass_s"] = stats.render.photons;
        state.counters["camera_pass_s"] = stats.render.camera_paths;
        state.counters["scatter_s"] = stats.render.gather;
        // Camera and shadow rays over the camera pass's tracing time (its gathers excluded).
        if (stats.render.camera_paths > 0)
            g_camera_rays_per_s = std::max(g_camera_rays_per_s, stats.counts.camera_rays / stats.render.camera_paths);
    }
}

// The photon pass alone (tracing and the photon grid), as the renderer runs it.
void BM_PhotonPass(benchmark::State& state) {
    sl::SceneDesc scene = cornell(1);
    sl::RenderContext ctx(scene);
    sl::SectionLayout layout = sl::make_section(ctx.timeline, ctx.emission, 1, 0);
    sl::PhotonMap map;
    int pass = 0;
    for (auto _ : state) {
        sl::PhotonTraceCounters counters;
        double trace_s = 0, grid_s = 0;
        for (int i = 0; i < 4; ++i) {  // build() is these two steps (the cell size known to both): timed apart
            auto t0 = Clock::now();
            map.trace(ctx, layout, pass++, scene.render.photons_per_pass, counters, false, nullptr, ctx.initial_radius);
            auto t1 = Clock::now();
            map.finish(ctx, ctx.initial_radius, counters, nullptr);
            trace_s += std::chrono::duration<double>(t1 - t0).count();
            grid_s += std::chrono::duration<double>(Clock::now() - t1).count();
        }
        const double secs = trace_s + grid_s;
        state.SetIterationTime(secs);
        state.counters["trace_s"] = trace_s;
        state.counters["grid_s"] = grid_s;
        g_photon_rays_per_s = std::max(g_photon_rays_per_s, counters.rays.load() / secs);
        g_photon_trace_rays_per_s = std::max(g_photon_trace_rays_per_s, counters.rays.load() / trace_s);
        state.counters["rays_per_s"] = counters.rays.load() / secs;
    }
}

// Random rays through the same BVH: origins uniform in the scene's box, directions uniform.
void BM_BareEmbree(benchmark::State& state) {
    sl::SceneDesc scene = cornell(1);
    sl::RenderContext ctx(scene);
    const size_t batches = 512, per_batch = 4096;
    for (auto _ : state) {
        auto t0 = Clock::now();
        const uint64_t hits = sl::bench::trace_random_rays(ctx, batches, per_batch, 0);  // same rays each round
        double secs = std::chrono::duration<double>(Clock::now() - t0).count();
        state.SetIterationTime(secs);
        g_bare_rays_per_s = std::max(g_bare_rays_per_s, batches * per_batch / secs);
        benchmark::DoNotOptimize(hits);
    }
}

}  // namespace

int main(int argc, char** argv) {
    for (int i = 1; i + 1 < argc; ++i) {
        if (!std::strcmp(argv[i], "--passes")) g_passes = std::atoi(argv[i + 1]);
        if (!std::strcmp(argv[i], "--photons")) g_photons = std::atoll(argv[i + 1]);
        if (!std::strcmp(argv[i], "--rounds")) g_rounds = std::atoi(argv[i + 1]);
    }
    // Interleave the frame counts round by round so that machine noise hits them alike.
    for (int round = 0; round < g_rounds; ++round) {
        for (int f : {1, 8, 48, 192})
            benchmark::RegisterBenchmark(("render/frames:" + std::to_string(f)).c_str(), BM_Render)
                ->Arg(f)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark("photon_pass/4_passes", BM_PhotonPass)
            ->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark("bare_embree/random_rays", BM_BareEmbree)
            ->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
    }
    // Google Benchmark's own flags (e.g. --benchmark_filter=photon_pass for a profile) pass
    // through; it leaves ours alone.
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();

    std::printf("\nCornell box 256x256, %d passes x %lld photons, best of %d rounds\n", g_passes, g_photons, g_rounds);
    std::printf("%8s %12s %12s %12s %12s\n", "frames", "seconds", "vs F=1", "cpu seconds", "vs F=1");
    for (auto [f, s] : g_best_seconds)
        std::printf("%8d %12.3f %12.3f %12.3f %12.3f\n", f, s, s / g_best_seconds[1], g_best_cpu[f], g_best_cpu[f] / g_best_cpu[1]);
    std::printf("photon pass rays/s %.3g, bare Embree rays/s %.3g, ratio %.2f\n", g_photon_rays_per_s,
                g_bare_rays_per_s, g_photon_rays_per_s / g_bare_rays_per_s);
    std::printf("photon pass without its grid sort: rays/s %.3g, ratio to bare Embree %.2f\n", g_photon_trace_rays_per_s,
                g_photon_trace_rays_per_s / g_bare_rays_per_s);
    std::printf("camera pass rays/s %.3g (camera and shadow rays, its gathers excluded), ratio to bare Embree %.2f\n",
                g_camera_rays_per_s, g_camera_rays_per_s / g_bare_rays_per_s);
    return 0;
}
