// The cost of the participating medium, and that it does not grow with the number of frames.
//
//   ./build/bench_medium [--passes N] [--photons N] [--rounds N]   (samples/cornell_haze.json, 256x256)
//
// Prints, in one run: seconds per pass (camera pass, photon pass, gather) with and without the
// medium, and the beam radiance estimate's cost per camera segment (and photons gathered per
// segment), for F = 1 and F = 48 frames; the best of --rounds rounds, interleaved so that
// machine noise hits every case alike. Wall time and process CPU time: on a shared machine the
// CPU time is the steadier measure of the work itself.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <map>
#include <string>

#include "config/parse_scene.h"
#include "stages/render/render_context.h"
#include "pipeline/frames_in_memory.h"
#include "pipeline/render_frames.h"

namespace {

using Clock = std::chrono::steady_clock;
int g_passes = 8, g_rounds = 3;
long long g_photons = 100000;

struct Best {
    double pass_s = 0, camera_s = 0, photons_s = 0, gather_s = 0, beam_s = 0;
    double beam_ns_per_segment = 0, hits_per_segment = 0, segments_per_pass = 0;
    double pass_cpu_s = 0, beam_cpu_ns_per_segment = 0;  // process CPU time: robust to a busy machine
};
std::map<std::pair<int, bool>, Best> g_best;  // (F, medium) -> fastest round

sl::SceneDesc scene(int frames, bool medium) {
    sl::SceneDesc s = sl::parse_scene_file(std::string(SLOWLIGHT_SOURCE_DIR) + "/samples/cornell_haze.json");
    s.camera.width = s.camera.height = 256;
    s.time.frames = frames;
    s.render.passes = g_passes;
    s.render.photons_per_pass = g_photons;
    s.medium.present = medium;
    return s;
}

void BM_Pass(benchmark::State& state) {
    const int frames = static_cast<int>(state.range(0));
    const bool medium = state.range(1) != 0;
    sl::SceneDesc s = scene(frames, medium);
    sl::RenderContext ctx(s);
    for (auto _ : state) {
        sl::FramesInMemory sink;
        sink.keep_frames = false;
        auto t0 = Clock::now();
        std::clock_t c0 = std::clock();
        double cpu = 0, secs = 0;
        sink.on_section_rendered = [&](int, const sl::SectionBuffer&) {  // the passes alone, not the frames
            cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
            secs = std::chrono::duration<double>(Clock::now() - t0).count();
        };
        const sl::PipelineStats run = sl::render_frames(ctx, {}, sink);
        state.SetIterationTime(secs);
        const double n = s.render.passes;
        Best b;
        b.pass_s = secs / n;
        b.camera_s = run.render.camera_paths / n;
        b.photons_s = run.render.photons / n;
        b.gather_s = run.render.gather / n;
        b.beam_s = run.render.volume / n;
        double segs = static_cast<double>(run.counts.beam_segments);
        b.segments_per_pass = segs / n;
        b.beam_ns_per_segment = segs > 0 ? run.render.volume * 1e9 / segs : 0;
        b.pass_cpu_s = cpu / n;
        b.beam_cpu_ns_per_segment = segs > 0 ? run.render.volume_cpu * 1e9 / segs : 0;
        b.hits_per_segment = segs > 0 ? run.counts.beam_hits / segs : 0;
        // The best of each number on its own, over the rounds.
        Best& best = g_best[{frames, medium}];
        auto keep = [](double& kept, double v) { kept = kept == 0 ? v : std::min(kept, v); };
        keep(best.pass_s, b.pass_s);
        keep(best.camera_s, b.camera_s);
        keep(best.photons_s, b.photons_s);
        keep(best.gather_s, b.gather_s);
        keep(best.beam_s, b.beam_s);
        keep(best.beam_ns_per_segment, b.beam_ns_per_segment);
        keep(best.pass_cpu_s, b.pass_cpu_s);
        keep(best.beam_cpu_ns_per_segment, b.beam_cpu_ns_per_segment);
        best.hits_per_segment = b.hits_per_segment;
        best.segments_per_pass = b.segments_per_pass;
        state.counters["s_per_pass"] = b.pass_s;
        state.counters["beam_ns_per_ray"] = b.beam_ns_per_segment;
    }
}

}  // namespace

int main(int argc, char** argv) {
    for (int i = 1; i + 1 < argc; ++i) {
        if (!std::strcmp(argv[i], "--passes")) g_passes = std::atoi(argv[i + 1]);
        if (!std::strcmp(argv[i], "--photons")) g_photons = std::atoll(argv[i + 1]);
        if (!std::strcmp(argv[i], "--rounds")) g_rounds = std::atoi(argv[i + 1]);
    }
    for (int round = 0; round < g_rounds; ++round)
        for (int f : {1, 48})
            for (int m : {0, 1})
                benchmark::RegisterBenchmark(("pass/frames:" + std::to_string(f) + (m ? "/medium" : "/vacuum")).c_str(),
                                             BM_Pass)
                    ->Args({f, m})->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
    int bargc = 1;
    benchmark::Initialize(&bargc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();

    std::printf("\nCornell box with haze (sigma_s 0.3, sigma_a 0.02 /m) 256x256, %d passes x %lld photons, best of %d rounds\n",
                g_passes, g_photons, g_rounds);
    std::printf("wall seconds per pass (stages: best of each), CPU seconds per pass (both threads), beam estimate per camera segment\n");
    std::printf("%6s %7s %8s %8s %8s %8s %8s %9s %12s %12s %9s\n", "frames", "medium", "s/pass", "camera", "photons",
                "gather", "beam", "cpu/pass", "beam ns/ray", "beam cpu ns", "hits/ray");
    for (auto& [key, b] : g_best)
        std::printf("%6d %7s %8.4f %8.4f %8.4f %8.4f %8.4f %9.4f %12.0f %12.0f %9.1f\n", key.first,
                    key.second ? "on" : "off", b.pass_s, b.camera_s, b.photons_s, b.gather_s, b.beam_s, b.pass_cpu_s,
                    b.beam_ns_per_segment, b.beam_cpu_ns_per_segment, b.hits_per_segment);
    auto ratio = [](double a, double b) { return b > 0 ? a / b : 0.0; };
    const Best &v1 = g_best[{1, false}], &v48 = g_best[{48, false}], &m1 = g_best[{1, true}], &m48 = g_best[{48, true}];
    std::printf("pass with medium / without: F=1 %.2f, F=48 %.2f (CPU: %.2f, %.2f)\n", ratio(m1.pass_s, v1.pass_s),
                ratio(m48.pass_s, v48.pass_s), ratio(m1.pass_cpu_s, v1.pass_cpu_s), ratio(m48.pass_cpu_s, v48.pass_cpu_s));
    std::printf("F=48 / F=1, wall: pass without medium %.3f, with medium %.3f, beam estimate per ray %.3f\n",
                ratio(v48.pass_s, v1.pass_s), ratio(m48.pass_s, m1.pass_s),
                ratio(m48.beam_ns_per_segment, m1.beam_ns_per_segment));
    std::printf("F=48 / F=1, CPU:  pass without medium %.3f, with medium %.3f, beam estimate per ray %.3f\n",
                ratio(v48.pass_cpu_s, v1.pass_cpu_s), ratio(m48.pass_cpu_s, m1.pass_cpu_s),
                ratio(m48.beam_cpu_ns_per_segment, m1.beam_cpu_ns_per_segment));
    return 0;
}
