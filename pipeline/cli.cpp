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
#include "pipeline/resume.h"
#include "pipeline/retime.h"
#include "pipeline/run_stats.h"
#include "pipeline/settings_hash.h"
#include "pipeline/scene_info.h"
#include "core/import/model_scene.h"
#include "core/import/resolve_imports.h"

namespace sl {
namespace {

std::atomic<bool> g_cancel{false};

extern "C" void on_signal(int) {
    if (g_cancel.exchange(true)) _exit(130);  // a second signal: stop at once
}

// Refuse up front what could only end in running out of memory.
void check_fits_machine(const MemoryPlan& plan) {
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || page <= 0) return;
    uint64_t ram = static_cast<uint64_t>(pages) * static_cast<uint64_t>(page);
    uint64_t need = plan.buffers_in_flight() + plan.fixed_overhead_bytes;
    if (need > ram)
        throw InputError("the render needs about " + format_bytes(need) + " (" + format_bytes(plan.buffers_in_flight()) +
                         " of time buckets with " + std::to_string(plan.sections) + " section(s)), more than this machine's " +
                         format_bytes(ram) + "; use --sections, --max-memory, fewer frames or a smaller image");
}

SceneDesc load_scene(const RunOptions& o) {
    SceneDesc scene = o.scene_path.empty()              ? parse_default_scene()
                      : is_model_file(o.scene_path) ? scene_for_model(o.scene_path)
                                                    : parse_scene_file(o.scene_path);
    resolve_imports(scene);  // meshes, materials, textures and lights of imported files
    apply_overrides(scene, o.overrides);
    return scene;
}

int render(const RunOptions& o) {
    auto t0 = std::chrono::steady_clock::now();
    SceneDesc scene = load_scene(o);
    MemoryPlan plan = plan_memory(scene, o);
    check_fits_machine(plan);
    if (o.resume && !o.cube_path.empty())
        throw InputError("command line: --cube cannot be combined with --resume (the cube needs every section)");
    const std::string fingerprint = settings_fingerprint(scene, plan.sections, o.strategy);

    RenderContext ctx(scene);  // meshes and the BVH: input errors here come before any output exists

    OutputSettings out;
    out.video = o.output;
    out.exr_dir = o.exr_dir;
    out.png_dir = o.png_dir;
    out.cube = o.cube_path;
    out.width = scene.camera.width;
    out.height = scene.camera.height;
    out.frames = scene.time.frames;
    out.fps = scene.time.fps;
    out.start_ns = scene.time.start_ns;
    out.end_ns = scene.time.end_ns;
    out.exposure = o.exposure;
    out.metadata = {{"slowlight:version", SLOWLIGHT_VERSION}, {"slowlight:scene", scene.source},
                    {kFingerprintKey, fingerprint}};
    FrameOutputs outputs(out);  // every output is checked before rendering starts

    PipelineJob job;
    job.ctx = &ctx;
    job.plan = plan;
    job.strategy = o.strategy;
    if (o.resume) job.on_disk = sections_on_disk(outputs, plan_sections(ctx, plan, o.strategy), fingerprint);
    std::fprintf(stderr, "slowlight: %dx%d, %d frames, %d passes x %lld photons, %d section%s%s; buckets %s per section, about %s fixed\n",
                 ctx.width, ctx.height, scene.time.frames, scene.render.passes,
                 static_cast<long long>(scene.render.photons_per_pass), plan.sections, plan.sections > 1 ? "s" : "",
                 plan.overlap ? " (two alive: encode while rendering)" : "",
                 format_bytes(plan.buffer_bytes_per_section).c_str(), format_bytes(plan.fixed_overhead_bytes).c_str());
    double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    ProgressBar bar(o.progress, plan.sections, scene.render.passes);
    PipelineStats stats = run_pipeline(job, outputs, [&](int s, int p) { bar.update(s, p); }, g_cancel);
    if (stats.sections_resumed > 0)
        std::fprintf(stderr, "slowlight: resumed %d of %d sections from %s\n", stats.sections_resumed, plan.sections,
                     o.exr_dir.c_str());
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
        case RunOptions::Command::Retime: break;
        case RunOptions::Command::Render: break;
        }
        std::unique_ptr<tbb::global_control> threads;
        if (o.threads > 0)
            threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);
        if (o.command == RunOptions::Command::Retime) return retime(o);
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
