#include "pipeline/cli.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <unistd.h>

#include "config/command_line.h"
#include "config/parse_scene.h"
#include "core/errors.h"
#include "pipeline/frame_outputs.h"
#include "pipeline/memory_plan.h"
#include "pipeline/progress.h"
#include "pipeline/render_pipeline.h"
#include "pipeline/run_stats.h"
#include "pipeline/scene_info.h"

namespace sl {
namespace {

std::atomic<bool> g_cancel{false};

extern "C" void on_signal(int) {
    if (g_cancel.exchange(true)) _exit(130);  // a second signal: stop at once
}

SceneDesc load_scene(const RunOptions& o) {
    SceneDesc scene = o.scene_path.empty() ? parse_default_scene() : parse_scene_file(o.scene_path);
    apply_overrides(scene, o.overrides);
    return scene;
}

int render(const RunOptions& o) {
    auto t0 = std::chrono::steady_clock::now();
    SceneDesc scene = load_scene(o);
    MemoryPlan plan = plan_memory(scene, o);

    OutputSettings out;
    out.video = o.output;
    out.exr_dir = o.exr_dir;
    out.png_dir = o.png_dir;
    out.width = scene.camera.width;
    out.height = scene.camera.height;
    out.fps = scene.time.fps;
    out.exposure = o.exposure;
    out.metadata = {{"slowlight:version", SLOWLIGHT_VERSION}, {"slowlight:scene", scene.source}};
    FrameOutputs outputs(out);  // every output is checked before rendering starts

    RenderContext ctx(scene);
    std::fprintf(stderr, "slowlight: %dx%d, %d frames, %d passes x %lld photons, %d section%s%s; buckets %s per section, about %s fixed\n",
                 ctx.width, ctx.height, scene.time.frames, scene.render.passes,
                 static_cast<long long>(scene.render.photons_per_pass), plan.sections, plan.sections > 1 ? "s" : "",
                 plan.overlap ? " (two alive: encode while rendering)" : "",
                 format_bytes(plan.buffer_bytes_per_section).c_str(), format_bytes(plan.fixed_overhead_bytes).c_str());
    double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    ProgressBar bar(o.progress, plan.sections, scene.render.passes);
    PipelineStats stats = run_pipeline(ctx, plan, o.strategy, outputs,
                                       [&](int s, int p) { bar.update(s, p); }, g_cancel);
    bar.finish();
    auto tf = std::chrono::steady_clock::now();
    outputs.finish();
    double output_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - tf).count();

    if (!o.stats_path.empty()) {
        RunSummary summary;
        summary.scene = &scene;
        summary.plan = plan;
        summary.pipeline = stats;
        summary.setup_seconds = setup;
        summary.output_seconds = output_seconds;
        summary.exposure = outputs.exposure().value_or(1.0);
        summary.strategy = o.strategy;
        summary.threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
        summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        write_stats_json(o.stats_path, summary);
    }
    if (stats.interrupted) {
        std::fprintf(stderr, "slowlight: interrupted; %lld frames written\n", static_cast<long long>(outputs.frames_written));
        return 130;
    }
    return 0;
}

}  // namespace

int run_cli(int argc, char** argv) {
    try {
        RunOptions o = parse_command_line(argc, argv);
        switch (o.command) {
        case RunOptions::Command::Help: std::cout << usage_text(); return 0;
        case RunOptions::Command::Version: std::cout << "slowlight " << SLOWLIGHT_VERSION << "\n"; return 0;
        case RunOptions::Command::Info: {
            SceneDesc scene = load_scene(o);
            print_scene_info(std::cout, scene);
            return 0;
        }
        case RunOptions::Command::Render: break;
        }
        std::unique_ptr<tbb::global_control> threads;
        if (o.threads > 0)
            threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);
        return render(o);
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "error: out of memory\n");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}

}  // namespace sl
