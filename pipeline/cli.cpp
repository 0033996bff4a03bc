#include "pipeline/cli.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <unistd.h>

#include "config/command_line.h"
#include "config/parse_scene.h"
#include "core/errors.h"
#include "config/duration.h"
#include "pipeline/checkpoint.h"
#include "pipeline/frame_outputs.h"
#include "pipeline/memory_plan.h"
#include "pipeline/progress.h"
#include "pipeline/render_pipeline.h"
#include "pipeline/preview_sheet.h"
#include "pipeline/resume.h"
#include "pipeline/resume_checkpoints.h"
#include "pipeline/resume_command.h"
#include "pipeline/retime.h"
#include "pipeline/run_stats.h"
#include "pipeline/settings_hash.h"
#include "pipeline/scene_info.h"
#include "pipeline/time_budget.h"

namespace sl {
namespace {

std::atomic<bool> g_cancel{false};
// Until outputs are opened nothing has been written, so a signal then ends the run at once.
std::atomic<bool> g_setting_up{true};

extern "C" void on_signal(int) {
    if (g_setting_up.load()) {
        static const char msg[] = "slowlight: interrupted during set-up; nothing written\n";
        ssize_t ignored = write(STDERR_FILENO, msg, sizeof msg - 1);
        (void)ignored;
        _exit(130);
    }
    if (g_cancel.exchange(true)) _exit(130);  // a second signal: stop at once
    static const char msg[] = "\nslowlight: interrupted: ending the pass in flight, then saving the section and "
                              "writing its frames (interrupt again to quit at once)\n";
    ssize_t ignored = write(STDERR_FILENO, msg, sizeof msg - 1);
    (void)ignored;
}

// "frames 0-23 (sections 1-2, section 2 from 12 of 64 passes) to out.mp4 and exr/"
std::string what_was_written(const PipelineStats& stats, const FrameOutputs& outputs, const RunOptions& o, int passes) {
    if (outputs.frames_written == 0) return "nothing written";
    std::string where;
    auto add = [&](const std::string& w) { where += (where.empty() ? "" : ", ") + w; };
    if (!o.output.empty()) add(o.output == "-" ? std::string("stdout") : o.output);
    if (!o.exr_dir.empty()) add(o.exr_dir + "/");
    if (!o.png_dir.empty()) add(o.png_dir + "/");
    std::string text = "wrote frames 0-" + std::to_string(outputs.frames_written - 1);
    if (stats.interrupted_section >= 0)
        text += " (section " + std::to_string(stats.interrupted_section + 1) + " from " +
                std::to_string(stats.passes_per_section[stats.interrupted_section]) + " of " + std::to_string(passes) +
                " passes)";
    return text + (where.empty() ? " (to no output: none was asked for)" : " to " + where);
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
    SceneDesc scene = o.scene_path.empty() ? parse_default_scene() : parse_scene_file(o.scene_path);
    apply_overrides(scene, o.overrides);
    return scene;
}

int render(const RunOptions& o, const std::vector<std::string>& argv) {
    auto t0 = std::chrono::steady_clock::now();
    g_setting_up = true;
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    SceneDesc scene = load_scene(o);
    MemoryPlan plan = plan_memory(scene, o);
    check_fits_machine(plan);
    if (o.resume && !o.cube_path.empty())
        throw InputError("command line: --cube cannot be combined with --resume (the cube needs every section)");
    const std::string fingerprint = settings_fingerprint(scene, plan.sections, o.strategy);

    RenderContext ctx(scene);  // meshes and the BVH: input errors here come before any output exists

    // Checkpoints: in --checkpoint DIR, or else in --exr-dir, where --resume looks anyway.
    const std::string again = resume_command(argv);
    CheckpointSettings checkpoints;
    checkpoints.dir = !o.checkpoint_dir.empty() ? o.checkpoint_dir : o.exr_dir;
    checkpoints.flag = !o.checkpoint_dir.empty() ? "--checkpoint" : "--exr-dir";
    checkpoints.every = o.checkpoint_every.value_or(kDefaultCheckpointEvery);
    checkpoints.keep_finished = o.exr_dir.empty() && plan.sections > 1;
    SectionStateId state_id;
    state_id.program_version = SLOWLIGHT_VERSION;
    state_id.fingerprint = fingerprint;
    state_id.sections = plan.sections;
    state_id.passes_target = scene.render.passes;
    state_id.width = ctx.width;
    state_id.height = ctx.height;
    const std::vector<SectionLayout> layouts = plan_sections(ctx, plan, o.strategy);
    std::vector<SectionStart> starts;
    if (o.resume)
        starts = checkpoints_to_resume(checkpoints.dir, state_id, layouts, ctx.has_ambient());
    else
        refuse_existing_checkpoints(checkpoints.dir, again);

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
    if (!o.preview_path.empty()) {  // checked now: a preview that cannot be written must not stop a render
        std::filesystem::path dir = std::filesystem::path(o.preview_path).parent_path();
        std::error_code ec;
        if (std::filesystem::is_directory(o.preview_path, ec) || !std::filesystem::is_directory(dir.empty() ? "." : dir, ec))
            throw RuntimeFailure("--preview " + o.preview_path + ": cannot write there (" +
                                 (std::filesystem::is_directory(o.preview_path, ec) ? std::string("a directory")
                                                                                     : "no directory " + dir.string()) +
                                 ")");
    }
    g_setting_up = false;  // from here on a signal means: deliver what you have
    Checkpointer checkpointer(checkpoints, state_id);  // makes the directory: checked before any output
    FrameOutputs outputs(out);  // every output is checked before rendering starts

    PipelineJob job;
    job.ctx = &ctx;
    job.plan = plan;
    job.strategy = o.strategy;
    if (o.resume && !o.exr_dir.empty()) {
        job.on_disk = sections_on_disk(outputs, layouts, fingerprint);
        drop_interrupted_sections(outputs, layouts, job.on_disk);
    }
    job.starts = starts;
    if (checkpointer.enabled()) job.checkpointer = &checkpointer;
    int to_render = 0;
    for (int s = 0; s < plan.sections; ++s)
        to_render += !(s < static_cast<int>(job.on_disk.size()) && job.on_disk[s]) &&
                     !(s < static_cast<int>(starts.size()) && starts[s].finished);
    TimeBudget budget = o.time_limit ? TimeBudget(*o.time_limit, t0, to_render) : TimeBudget();
    if (budget.limited()) job.budget = &budget;
    PreviewSheet preview(o.preview_path, scene.emission.mode, ctx.pulse_buckets, ctx.width, ctx.height);
    if (preview.enabled()) job.preview = &preview;
    std::fprintf(stderr, "slowlight: %dx%d, %d frames, %d passes x %lld photons, %d section%s%s; buckets %s per section, about %s fixed\n",
                 ctx.width, ctx.height, scene.time.frames, scene.render.passes,
                 static_cast<long long>(scene.render.photons_per_pass), plan.sections, plan.sections > 1 ? "s" : "",
                 plan.overlap ? " (two alive: encode while rendering)" : "",
                 format_bytes(plan.buffer_bytes_per_section).c_str(), format_bytes(plan.fixed_overhead_bytes).c_str());
    double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    ProgressBar bar(o.progress, plan.sections, scene.render.passes, scene.render.alpha);
    for (int s = 0; s < plan.sections; ++s)
        if ((s < static_cast<int>(job.on_disk.size()) && job.on_disk[s]) || (s < static_cast<int>(starts.size()) && starts[s].finished))
            bar.skip_section(s);
    if (budget.limited())
        bar.set_deadline(*o.time_limit - std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    job.log = [&](const std::string& line) { bar.message(line); };
    job.section_started = [&](int s, int p) { bar.section_started(s, p); };
    job.full_pass_seconds = [&](double t, int n) { bar.expect_full_pass(t, n); };
    job.passes_fixed = [&](int n) { bar.set_passes(n); };
    PipelineStats stats = run_pipeline(job, outputs, [&](int s, int p) { bar.update(s, p); }, g_cancel);
    bar.finish();
    if (stats.sections_resumed > 0)
        std::fprintf(stderr, "slowlight: resumed %d of %d sections from %s\n", stats.sections_resumed, plan.sections,
                     (o.exr_dir.empty() ? checkpoints.dir : o.exr_dir).c_str());
    if (budget.limited() && !stats.interrupted) {
        int reached = budget.passes().value_or(scene.render.passes);
        std::fprintf(stderr, "slowlight: time limit %s: %d pass%s per section (--passes %d)\n",
                     format_duration(*o.time_limit).c_str(), reached, reached == 1 ? "" : "es", scene.render.passes);
    }
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
        std::string where = stats.interrupted_section >= 0
                                ? "in section " + std::to_string(stats.interrupted_section + 1) + "/" + std::to_string(plan.sections)
                                : std::string("before a section's first pass");
        std::fprintf(stderr, "slowlight: interrupted %s; %s\n", where.c_str(),
                     what_was_written(stats, outputs, o, scene.render.passes).c_str());
        if (checkpointer.enabled())
            std::fprintf(stderr, "slowlight: %s; to continue: %s\n",
                         stats.interrupted_checkpoint.empty() ? ("finished frames are in " + o.exr_dir).c_str()
                                                              : ("state saved in " + stats.interrupted_checkpoint).c_str(),
                         again.c_str());
        else
            std::fprintf(stderr, "slowlight: nothing saved to resume from (give --checkpoint DIR or --exr-dir to make a "
                                 "render resumable)\n");
        return 130;
    }
    checkpointer.remove_all();  // a finished render needs none of them
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
        return render(o, std::vector<std::string>(argv, argv + argc));
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
