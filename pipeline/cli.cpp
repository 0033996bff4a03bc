#include "pipeline/cli.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <unistd.h>

#include "config/command_line.h"
#include "config/parse_scene.h"
#include "core/errors.h"
#include "pipeline/distributed/mpi_launch.h"
#include "pipeline/distributed/rank_start.h"
#include "config/text_util.h"
#include "pipeline/exposure.h"
#include "pipeline/frame_outputs.h"
#include "pipeline/memory_plan.h"
#include "pipeline/output_checks.h"
#include "pipeline/progress.h"
#include "pipeline/render_pipeline.h"
#include "pipeline/resume.h"
#include "pipeline/retime.h"
#include "pipeline/run_stats.h"
#include "pipeline/settings_hash.h"
#include "pipeline/scene_checks.h"
#include "stages/output/atomic_file.h"
#include "pipeline/scene_info.h"
#include "core/import/model_scene.h"
#include "core/import/resolve_imports.h"

namespace sl {
namespace {

std::atomic<bool> g_cancel{false};

extern "C" void on_signal(int) {
    if (g_cancel.exchange(true)) {  // a second signal: stop at once, leaving no temporary behind
        remove_live_temporaries();
        _exit(130);
    }
}

// Several ranks (MPI): the exchange, and whether the ranks agreed to start rendering (before
// that, a failure is agreed on; after it, a failing rank ends the whole job).
struct Ranks {
    RankExchange* ex = nullptr;
    bool concurrent_channels = false;
    bool started = false;
    bool root() const { return !ex || ex->rank() == 0; }
};
Ranks g_ranks;

// Under MPI the launcher stops every rank with SIGTERM when one of them died: say so, from
// rank 0, as the job's one error line (a rank blocked in a collective would never get to it).
extern "C" void on_launcher_signal(int sig) {
    if (!g_ranks.started || g_cancel.load()) {
        if (g_cancel.exchange(true)) _exit(130);
        return;
    }
    if (g_ranks.root()) {
        const char msg[] = "error: the MPI launcher stopped this render (another rank has died or was killed); "
                           "its outputs are incomplete\n";
        ssize_t ignored = write(STDERR_FILENO, msg, sizeof msg - 1);
        (void)ignored;
    }
    _exit(128 + sig);
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

// The last line of a run: what was written, how many frames, how long it took.
void print_final_line(const FrameOutputs& outputs, const std::string& stats_path,
                      std::chrono::steady_clock::time_point t0) {
    std::string what = outputs.summary();
    if (!stats_path.empty()) what += (what.empty() ? "" : ", ") + stats_path + " (statistics)";
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "slowlight: wrote %s in %.1f s\n", what.c_str(), seconds);
}

// `slowlight info cube.npy`: a cube is not a scene; say what to do with it.
void refuse_cube_as_scene(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) return;  // missing: the scene reader says so
    char magic[6] = {};
    f.read(magic, 6);
    const bool npy = f.gcount() == 6 && std::string_view(magic, 6) == "\x93NUMPY";
    if (npy || path.ends_with(".npy"))
        throw InputError(printable(path) + ": this is a transient cube (render --cube), not a scene; make a video of it with "
                         "slowlight retime " + printable(path) + " -o out.mp4");
}

SceneDesc load_scene(const RunOptions& o) {
    if (!o.scene_path.empty()) refuse_cube_as_scene(o.scene_path);
    SceneDesc scene = o.scene_path.empty()              ? parse_default_scene()
                      : is_model_file(o.scene_path) ? scene_for_model(o.scene_path)
                                                    : parse_scene_file(o.scene_path);
    resolve_imports(scene);  // meshes, materials, textures and lights of imported files
    apply_overrides(scene, o.overrides);
    return scene;
}

int render(RunOptions o) {
    auto t0 = std::chrono::steady_clock::now();
    RankExchange* ex = g_ranks.ex;
    const bool root = g_ranks.root();
    if (ex) {
        if (o.ranks > 0 && o.ranks != ex->ranks())
            throw InputError("command line: --ranks " + std::to_string(o.ranks) + ": this render runs on " +
                             std::to_string(ex->ranks()) + " MPI ranks");
        // Resuming needs the checkpoint of every rank's pixels: not yet.
        if (o.resume) throw InputError("command line: --resume is not supported yet when several MPI ranks render");
        o.ranks = ex->ranks();
    } else if (o.ranks > 1) {
        throw InputError("command line: --ranks " + std::to_string(o.ranks) +
                         ": a render on several ranks is started by an MPI launcher (mpirun -np N slowlight render ...); "
                         "--ranks is for info");
    }
    SceneDesc scene = load_scene(o);
    MemoryPlan plan = plan_memory(scene, o);
    // Rendering one section while rank 0 writes another uses both channels at once.
    if (ex && !g_ranks.concurrent_channels) plan.overlap = false;
    check_fits_machine(plan);
    if (o.resume && !o.cube_path.empty())
        throw InputError("command line: --cube cannot be combined with --resume (the cube needs every section)");
    check_outputs(outputs_of(o), scene.input_files);  // no clobbered input, nothing unwritable found late
    RenderContext ctx(scene);  // meshes and the BVH: input errors here come before any output exists
    ctx.exchange = ex;
    if (root)
        for (const std::string& w : scene_warnings(ctx, scene_facts(ctx))) std::fprintf(stderr, "%s\n", w.c_str());
    // After the meshes were checked and loaded, so that their own limits speak first.
    const std::string fingerprint = settings_fingerprint(scene, plan.sections, o.strategy);

    require_an_output(o);  // after every check of the input, before any work
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
    out.tone = o.tone;
    out.label_time = o.label_time;
    if (!o.cube_path.empty()) out.emitter_runs = mask_runs(emitter_pixels(ctx));
    out.metadata = {{"slowlight:version", SLOWLIGHT_VERSION}, {"slowlight:scene", scene.source},
                    {kFingerprintKey, fingerprint}};
    // Only rank 0 writes; the others assemble their pixels and send them to it.
    FrameOutputs outputs(root ? out : OutputSettings{});  // every output is checked before rendering starts

    PipelineJob job;
    job.ctx = &ctx;
    job.plan = plan;
    job.strategy = o.strategy;
    job.exposure_rule.percentile = o.exposure_percentile;
    job.exposure_rule.follow = o.exposure_follow;
    job.fingerprint = fingerprint;
    if (o.resume)
        job.on_disk = sections_on_disk(outputs, plan_sections(ctx, plan, o.strategy), fingerprint, ctx.width, ctx.height);
    if (ex) {  // from here on every rank renders, or none does
        const int status = agree_to_start(*ex, 0, "");
        if (status != 0) return status;
        g_ranks.started = true;
    }
    if (root)
        std::fprintf(stderr, "slowlight: %dx%d, %d frames, %d passes x %lld photons, %d section%s%s; buckets %s per section%s, about %s fixed\n",
                     ctx.width, ctx.height, scene.time.frames, scene.render.passes,
                     static_cast<long long>(scene.render.photons_per_pass), plan.sections, plan.sections > 1 ? "s" : "",
                     plan.overlap ? " (two alive: encode while rendering)" : "",
                     format_bytes(plan.buffer_bytes_per_section).c_str(),
                     ex ? (" per rank on " + std::to_string(ex->ranks()) + " MPI ranks").c_str() : "",
                     format_bytes(plan.fixed_overhead_bytes).c_str());
    double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, ex ? on_launcher_signal : on_signal);
    ProgressBar bar(o.progress && root, plan.sections, scene.render.passes);
    PipelineStats stats = run_pipeline(job, outputs, [&](int s, int p) { bar.update(s, p); }, g_cancel);
    if (ex && root)
        std::fprintf(stderr, "slowlight: %d MPI ranks; rank 0 received %s with the passes (%s per pass per rank) and %s of frames\n",
                     ex->ranks(), format_bytes(stats.exchanged_received[0]).c_str(),
                     format_bytes(stats.exchanged_received[0] / static_cast<uint64_t>(std::max(1, stats.passes_run))).c_str(),
                     format_bytes(stats.exchanged_received[1]).c_str());
    if (stats.sections_resumed > 0)
        std::fprintf(stderr, "slowlight: resumed %d of %d sections from %s\n", stats.sections_resumed, plan.sections,
                     o.exr_dir.c_str());
    bar.finish();
    auto tf = std::chrono::steady_clock::now();
    outputs.finish();
    double output_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - tf).count();

    if (!o.stats_path.empty() && root) {
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
        if (root) std::fprintf(stderr, "slowlight: interrupted; %lld frames written\n", static_cast<long long>(outputs.frames_written));
        return 130;
    }
    if (!root) return 0;  // rank 0 speaks for the job
    if (stats.steady_black)
        std::fprintf(stderr,
                     "warning: %s: no light reached the camera except straight from the lights: every frame is black "
                     "but for them (are the lights pointing away, or outside the room? see slowlight info)\n",
                     scene.source.c_str());
    print_final_line(outputs, o.stats_path, t0);
    return 0;
}

}  // namespace

int run_cli(int argc, char** argv) {
    if (argc <= 1) {  // `slowlight` alone: what it can do
        std::fprintf(stderr, "error: command line: no command given (expected render, info or retime)\n\n%s",
                     commands_text().c_str());
        return 2;
    }
    // Under an MPI launcher with several processes: MPI, through its plugin (else nothing).
    DistributedStart dist = start_distributed(argc, argv);
    if (!dist.error.empty()) {
        std::fprintf(stderr, "error: %s\n", dist.error.c_str());
        return 1;
    }
    g_ranks.ex = dist.exchange.get();
    g_ranks.concurrent_channels = dist.concurrent_channels;
    // A failure: one line and the exit status; under MPI agreed with the other ranks before the
    // render starts (rank 0 prints it), and after that the failing rank ends the job.
    auto fail = [&](int code, const std::string& message) -> int {
        if (!g_ranks.ex) {
            std::fprintf(stderr, "error: %s\n", message.c_str());
            return code;
        }
        if (!g_ranks.started) return agree_to_start(*g_ranks.ex, code, message);
        std::fprintf(stderr, "error: rank %d: %s\n", g_ranks.ex->rank(), message.c_str());
        g_ranks.ex->abort(code);
        return code;  // not reached: abort ends the process
    };
    try {
        RunOptions o = parse_command_line(argc, argv);
        const bool quiet = !g_ranks.root();  // one answer from the job, rank 0's
        switch (o.command) {
        case RunOptions::Command::Help: if (!quiet) std::cout << usage_text(o.help_topic); return 0;
        case RunOptions::Command::Version:
            if (!quiet) std::cout << "slowlight " << SLOWLIGHT_VERSION << "\n";
            return 0;
        case RunOptions::Command::Info: {
            SceneDesc scene = load_scene(o);
            if (g_ranks.ex) o.ranks = g_ranks.ex->ranks();
            if (!quiet) print_scene_info(std::cout, std::cerr, scene, o);
            return 0;
        }
        case RunOptions::Command::Retime:
            if (g_ranks.ex) throw InputError("command line: retime runs in one process; start it without mpirun");
            break;
        case RunOptions::Command::Render: break;
        }
        std::unique_ptr<tbb::global_control> threads;
        if (o.threads > 0)
            threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);
        if (o.command == RunOptions::Command::Retime) return retime(o);
        return render(o);
    } catch (const InputError& e) {
        return fail(2, e.what());
    } catch (const std::bad_alloc&) {
        return fail(1, "out of memory");
    } catch (const std::exception& e) {
        return fail(1, e.what());
    }
}

}  // namespace sl
