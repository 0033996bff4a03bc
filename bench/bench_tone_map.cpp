// Tone mapping one 512x512 frame to sRGB bytes, as the writer does for every video frame.
//
//   ./build/bench_tone_map
//
// Values spread over ~3 decades (a product of three uniforms in [0, 2)), exposure 1, all threads.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>
#include <vector>

#include "stages/output/tone_map.h"

namespace {

void BM_ToneMap512(benchmark::State& state) {
    const int w = 512, h = 512;
    std::vector<float> rgb(static_cast<size_t>(w) * h * 3);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(0, 2);
    for (float& v : rgb) v = u(rng) * u(rng) * u(rng);
    std::vector<uint8_t> out(rgb.size());
    for (auto _ : state) {
        sl::tone_map_srgb8(rgb.data(), w, h, 1.0, out.data());
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(rgb.size()));
}
BENCHMARK(BM_ToneMap512)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
