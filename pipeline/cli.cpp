#include "pipeline/cli.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sys/stat.h>
#include <unistd.h>

#include "config/command_line.h"
#include "config/parse_scene.h"
#include "foundation/errors.h"
#include "pipeline/distributed/mpi_launch.h"
#include "pipeline/distributed/rank_start.h"
#include "pipeline/distributed/resume_on_ranks.h"
#include "config/text_util.h"
#include "pipeline/exposure.h"
#include "config/duration.h"
#include "pipeline/checkpoint.h"
#include "pipeline/frame_outputs.h"
#include "pipeline/memory_plan.h"
#include "pipeline/output_checks.h"
#include "pipeline/progress.h"
#include "pipeline/render_messages.h"
#include "pipeline/render_pipeline.h"
#include "pipeline/render_setup.h"
#include "pipeline/preview_sheet.h"
#include "pipeline/resume.h"
#include "pipeline/resume_checkpoints.h"
#include "pipeline/resume_command.h"
#include "pipeline/retime.h"
#include "pipeline/run_stats.h"
#include "pipeline/settings_fingerprint.h"
#include "pipeline/scene_checks.h"
#include "stages/output/live_temporaries.h"
#include "pipeline/scene_info.h"
#include "core/import/model_scene.h"
#include "core/import/resolve_imports.h"
#include "pipeline/time_budget.h"

namespace sl {
namespace {

// What the signal handlers read and write. They run on whichever thread the signal lands, at
// any instruction, so they touch only lock-free atomics and call only async-signal-safe
// functions (write, unlink, _exit); everything else (saving the section, the last lines, the
// exit status) happens in normal code that watches g_cancel.
std::atomic<bool> g_cancel{false};
// Until outputs are opened nothing has been written, so a signal then ends the run at once.
std::atomic<bool> g_setting_up{true};
// Under MPI a launcher passes an interrupt to every rank: only rank 0 says so (one line per job).
std::atomic<bool> g_signal_lines{true};
// Under MPI: the ranks agreed to start rendering (a launcher's SIGTERM then means the job ends).
std::atomic<bool> g_ranks_started{false};
static_assert(std::atomic<bool>::is_always_lock_free, "read by signal handlers");

void say_from_handler(const char* text, size_t size) {
    const int saved_errno = errno;  // the interrupted code may be about to read it
    ssize_t ignored = write(STDERR_FILENO, text, size);
    (void)ignored;
    errno = saved_errno;
}

extern "C" void on_signal(int) {
    if (g_setting_up.load()) {
        static const char msg[] = "slowlight: interrupted during set-up; nothing written\n";
        if (g_signal_lines.load()) say_from_handler(msg, sizeof msg - 1);
        _exit(130);
    }
    // A second signal: stop at once, leaving no temporary behind (files already committed stay).
    if (g_cancel.exchange(true)) remove_live_temporaries_and_exit(130);
    static const char msg[] = "\nslowlight: interrupted: ending the pass in flight, then saving the section and "
                              "writing its frames (interrupt again to quit at once)\n";
    if (g_signal_lines.load()) say_from_handler(msg, sizeof msg - 1);
}

// Several ranks (MPI): the exchange, and whether the ranks agreed to start rendering (before
// that, a failure is agreed on; after it, a failing rank ends the whole job).
struct Ranks {
    RankExchange* ex = nullptr;
    bool concurrent_channels = false;
    bool started() const { return g_ranks_started.load(); }
    bool root() const { return !ex || ex->rank() == 0; }
};
Ranks g_ranks;

// Under MPI the launcher stops every rank with SIGTERM when one of them died: say so, from
// rank 0, as the job's one error line (a rank blocked in a collective would never get to it).
// The outputs are incomplete and stay so: their temporaries go.
extern "C" void on_launcher_signal(int sig) {
    if (!g_ranks_started.load() || g_cancel.load()) {
        if (g_cancel.exchange(true)) remove_live_temporaries_and_exit(130);
        return;
    }
    if (g_signal_lines.load()) {  // rank 0, cached before: no call into the exchange from here
        static const char msg[] = "error: the MPI launcher stopped this render (another rank has died or was killed); "
                                  "its outputs are incomplete\n";
        say_from_handler(msg, sizeof msg - 1);
    }
    remove_live_temporaries_and_exit(128 + sig);
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

// `slowlight info cube.npy`: a cube is not a scene; say what to do with it.
void refuse_cube_as_scene(const std::string& path) {
    struct stat st {};
    // Only a regular file is opened here: a FIFO or device would block (the scene reader then
    // refuses it with its own message).
    if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return;
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

int render(RunOptions o, const std::vector<std::string>& argv) {
    auto t0 = std::chrono::steady_clock::now();
    g_setting_up = true;
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    RankExchange* ex = g_ranks.ex;
    // Ctrl-C to Open MPI's mpirun cannot reach the ranks (it stops them with SIGTERM, as when a
    // rank died, and exits 1); SIGUSR1 it forwards: under MPI that is the interrupt of Ctrl-C.
    if (ex) std::signal(SIGUSR1, on_signal);
    const bool root = g_ranks.root();
    check_rank_options(o, ex);
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

    // Checkpoints: in --checkpoint DIR, or else in --exr-dir, where --resume looks anyway. With
    // several ranks, rank 0 alone reads and writes them (docs/distributed.md).
    const std::string again = resume_command(argv);
    const CheckpointSettings checkpoints = checkpoint_settings(o, plan);
    const SectionStateId state_id = section_state_id(scene, ctx, plan, fingerprint);
    const std::vector<SectionLayout> layouts = plan_sections(ctx, plan, o.strategy);
    std::vector<SectionStart> starts;
    if (o.resume && !ex)
        starts = checkpoints_to_resume(checkpoints.dir, state_id, layouts, ctx.has_ambient());
    else if (!o.resume && root)
        refuse_existing_checkpoints(checkpoints.dir, again);

    const OutputSettings out = output_settings(o, scene, ctx, fingerprint);
    if (root) check_preview_path(o.preview_path);  // by rank 0, its writer: a preview that cannot be written must not stop a render
    g_setting_up = false;  // from here on a signal means: deliver what you have
    Checkpointer checkpointer(checkpoints, state_id, ex);  // makes the directory: checked before any output
    // Only rank 0 writes; the others assemble their pixels and send them to it.
    FrameOutputs outputs(root ? out : OutputSettings{});  // every output is checked before rendering starts

    PipelineJob job;
    job.ctx = &ctx;
    job.plan = plan;
    job.strategy = o.strategy;
    job.exposure_rule.percentile = o.exposure_percentile;
    job.exposure_rule.follow = o.exposure_follow;
    job.fingerprint = fingerprint;
    job.exr_files = &outputs;
    auto frames_on_disk = [&](std::vector<bool>& on_disk) {
        if (!o.resume || o.exr_dir.empty()) return;
        on_disk = sections_on_disk(outputs, layouts, fingerprint, ctx.width, ctx.height);
        drop_interrupted_sections(outputs, layouts, on_disk);
    };
    if (o.resume && ex) {  // rank 0 judges, every rank gets its answer
        const int status = share_resume_plan(
            *ex,
            [&](std::vector<SectionStart>& st, std::vector<bool>& on_disk) {
                st = checkpoints_to_resume(checkpoints.dir, state_id, layouts, ctx.has_ambient());
                frames_on_disk(on_disk);
            },
            starts, job.on_disk);
        if (status != 0) return status;
    } else {
        frames_on_disk(job.on_disk);
    }
    job.starts = starts;
    if (checkpointer.enabled()) job.checkpointer = &checkpointer;
    int to_render = 0;
    for (int s = 0; s < plan.sections; ++s)
        to_render += !(s < static_cast<int>(job.on_disk.size()) && job.on_disk[s]) &&
                     !(s < static_cast<int>(starts.size()) && starts[s].finished);
    TimeBudget budget = o.time_limit ? TimeBudget(*o.time_limit, t0, to_render) : TimeBudget();
    if (budget.limited()) job.budget = &budget;
    PreviewSheet preview(o.preview_path, scene.emission.mode, ctx.timeline.pulse_buckets, ctx.width, ctx.height, ex);
    if (preview.enabled()) job.preview = &preview;
    if (ex) {  // from here on every rank renders, or none does
        const int status = agree_to_start(*ex, 0, "");
        if (status != 0) return status;
        g_ranks_started = true;
        std::signal(SIGTERM, on_launcher_signal);
    }
    if (root) print_render_start(ctx, scene, plan, ex);
    double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    ProgressBar bar(o.progress && root, plan.sections, scene.render.passes, scene.render.alpha);
    for (int s = 0; s < plan.sections; ++s)
        if ((s < static_cast<int>(job.on_disk.size()) && job.on_disk[s]) || (s < static_cast<int>(starts.size()) && starts[s].finished))
            bar.skip_section(s);
    if (budget.limited())
        bar.set_deadline(*o.time_limit - std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    job.log = [&](const std::string& line) { if (root) bar.message(line); };
    job.section_started = [&](int s, int p) { bar.section_started(s, p); };
    job.full_pass_seconds = [&](double t, int n) { bar.expect_full_pass(t, n); };
    job.passes_fixed = [&](int n) { bar.set_passes(n); };
    PipelineStats stats = run_pipeline(job, outputs, [&](int s, int p) { bar.update(s, p); }, g_cancel);
    bar.finish();
    if (root) print_after_render(stats, scene, plan, o, budget, o.exr_dir.empty() ? checkpoints.dir : o.exr_dir, ex);
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
        summary.time_limit = o.time_limit.value_or(0);
        summary.checkpoint_dir = checkpointer.enabled() ? checkpoints.dir : "";
        Checkpointer::Totals ct = checkpointer.totals();
        summary.checkpoint_writes = ct.writes;
        summary.checkpoint_bytes = ct.last_bytes;
        summary.checkpoint_seconds = ct.seconds;
        summary.checkpoint_longest = ct.longest;
        summary.preview_writes = preview.writes();
        summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        write_stats_json(o.stats_path, summary);
    }
    if (stats.interrupted) {
        if (!root) return 130;
        print_interrupted(stats, plan, outputs, o, scene.render.passes, checkpointer.enabled(), again);
        return 130;
    }
    checkpointer.remove_all();  // a finished render needs none of them
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
        // The one error line on stderr (as for any bad command line), the commands on stdout.
        std::fprintf(stderr, "error: command line: no command given (expected render, info or retime)\n");
        std::cout << commands_text();
        return 2;
    }
    // Under an MPI launcher with several processes: MPI, through its plugin (else nothing).
    DistributedStart dist = start_distributed(argc, argv);
    if (!dist.error.empty()) {
        if (dist.report_error) std::fprintf(stderr, "error: %s\n", dist.error.c_str());
        return 1;
    }
    g_ranks.ex = dist.exchange.get();
    g_signal_lines = g_ranks.root();
    g_ranks.concurrent_channels = dist.concurrent_channels;
    // A failure: one line and the exit status; under MPI agreed with the other ranks before the
    // render starts (rank 0 prints it), and after that the failing rank ends the job.
    auto fail = [&](int code, const std::string& message) -> int {
        if (!g_ranks.ex) {
            std::fprintf(stderr, "error: %s\n", message.c_str());
            return code;
        }
        if (!g_ranks.started()) return agree_to_start(*g_ranks.ex, code, message);
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
        return render(o, std::vector<std::string>(argv, argv + argc));
    } catch (const InputError& e) {
        return fail(2, e.what());
    } catch (const std::bad_alloc&) {
        return fail(1, "out of memory");
    } catch (const std::exception& e) {
        return fail(1, e.what());
    }
}

}  // namespace sl
