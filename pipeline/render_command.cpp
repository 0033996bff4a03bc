#include "pipeline/render_command.h"

#include <sys/stat.h>
#include <tbb/info.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string_view>

#include "config/command_line.h"
#include "config/parse_scene.h"
#include "config/text_util.h"
#include "core/import/model_scene.h"
#include "core/import/resolve_imports.h"
#include "foundation/errors.h"
#include "pipeline/checkpoint.h"
#include "pipeline/distributed/rank_start.h"
#include "pipeline/distributed/resume_on_ranks.h"
#include "pipeline/frame_outputs.h"
#include "pipeline/interrupts.h"
#include "pipeline/memory_plan.h"
#include "pipeline/output_checks.h"
#include "pipeline/preview_sheet.h"
#include "pipeline/progress.h"
#include "pipeline/render_messages.h"
#include "pipeline/render_pipeline.h"
#include "pipeline/render_setup.h"
#include "pipeline/resume.h"
#include "pipeline/resume_checkpoints.h"
#include "pipeline/resume_command.h"
#include "pipeline/run_stats.h"
#include "pipeline/scene_checks.h"
#include "pipeline/settings_fingerprint.h"
#include "pipeline/time_budget.h"

namespace sl {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

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

// One render command's state, step by step: what was read and checked, what is resumed, the
// outputs, the run.
class RenderCommand {
public:
    RenderCommand(RunOptions o, const std::vector<std::string>& argv, const RankSetup& ranks)
        : o_(std::move(o)), argv_(argv), ex_(ranks.ex), concurrent_channels_(ranks.concurrent_channels),
          root_(!ex_ || ex_->rank() == 0) {}

    // Every input read and checked, and every output checked, before anything is written.
    void read_and_check();
    // Where checkpoints go, and which ones a --resume continues from.
    void plan_checkpoints();
    // From here on a signal means: deliver what you have.
    void open_outputs();
    // What --resume finds done (frames on disk, finished checkpoints); the time budget and preview.
    int plan_the_run();
    int start_ranks();
    PipelineStats render();
    void write_stats(const PipelineStats& stats, double output_seconds);
    int conclude(const PipelineStats& stats);
    double finish_outputs();

private:
    bool done_before(int s) const {
        return (s < static_cast<int>(job_.on_disk.size()) && job_.on_disk[s]) ||
               (s < static_cast<int>(starts_.size()) && starts_[s].finished);
    }

    const Clock::time_point t0_ = Clock::now();
    RunOptions o_;
    const std::vector<std::string>& argv_;
    RankExchange* ex_;
    const bool concurrent_channels_;
    const bool root_;
    SceneDesc scene_;
    MemoryPlan plan_;
    std::unique_ptr<RenderContext> ctx_;
    std::string fingerprint_;
    std::string again_;  // the command that continues this render
    CheckpointSettings checkpoints_;
    SectionStateId state_id_;
    std::vector<SectionLayout> layouts_;
    std::vector<SectionStart> starts_;
    std::unique_ptr<Checkpointer> checkpointer_;
    std::unique_ptr<FrameOutputs> outputs_;
    std::unique_ptr<TimeBudget> budget_;
    std::unique_ptr<PreviewSheet> preview_;
    PipelineJob job_;
    double setup_seconds_ = 0;
};

void RenderCommand::read_and_check() {
    check_rank_options(o_, ex_);
    scene_ = load_scene(o_);
    plan_ = plan_memory(scene_, o_);
    // Rendering one section while rank 0 writes another uses both channels at once.
    if (ex_ && !concurrent_channels_) plan_.overlap = false;
    check_fits_machine(plan_);
    if (o_.resume && !o_.cube_path.empty())
        throw InputError("command line: --cube cannot be combined with --resume (the cube needs every section)");
    if (o_.resume && (!o_.hdf5_path.empty() || o_.sensors.any()))
        throw InputError(std::string("command line: ") +
                         (!o_.hdf5_path.empty() ? "--hdf5 cannot be combined with --resume (it needs"
                                                : "the sensor images (--phasor, --gate, --first-arrival) cannot be "
                                                  "combined with --resume (they need") +
                         " every section's bins)");
    check_sensor_request(o_.sensors, timeline_of(scene_), root_);
    check_outputs(outputs_of(o_), scene_.input_files);  // no clobbered input, nothing unwritable found late
    ctx_ = std::make_unique<RenderContext>(scene_);  // the BVH: input errors here come before any output exists
    ctx_->exchange = ex_;
    if (root_)
        for (const std::string& w : scene_warnings(*ctx_, scene_facts(*ctx_))) std::fprintf(stderr, "%s\n", w.c_str());
    // After the meshes were checked and loaded, so that their own limits speak first.
    fingerprint_ = settings_fingerprint(scene_, plan_.sections, o_.strategy);
    require_an_output(o_);  // after every check of the input, before any work
}

// In --checkpoint DIR, or else in --exr-dir, where --resume looks anyway. With several ranks,
// rank 0 alone reads and writes them (docs/distributed.md).
void RenderCommand::plan_checkpoints() {
    again_ = resume_command(argv_);
    checkpoints_ = checkpoint_settings(o_, plan_);
    state_id_ = section_state_id(scene_, *ctx_, plan_, fingerprint_);
    layouts_ = plan_sections(*ctx_, plan_, o_.strategy);
    if (o_.resume && !ex_) starts_ = checkpoints_to_resume(checkpoints_.dir, state_id_, layouts_, ctx_->has_ambient());
    else if (!o_.resume && root_) refuse_existing_checkpoints(checkpoints_.dir, again_);
}

void RenderCommand::open_outputs() {
    const OutputSettings out = output_settings(o_, scene_, *ctx_, fingerprint_);
    if (root_) check_preview_path(o_.preview_path);  // by rank 0, its writer: a preview that cannot be written must not stop a render
    outputs_opened();
    checkpointer_ = std::make_unique<Checkpointer>(checkpoints_, state_id_, ex_);  // makes the directory
    // Only rank 0 writes; the others assemble their pixels and send them to it.
    outputs_ = std::make_unique<FrameOutputs>(root_ ? out : OutputSettings{});  // every output checked now
}

int RenderCommand::plan_the_run() {
    job_.ctx = ctx_.get();
    job_.plan = plan_;
    job_.strategy = o_.strategy;
    job_.exposure_rule.percentile = o_.exposure_percentile;
    job_.exposure_rule.follow = o_.exposure_follow;
    job_.fingerprint = fingerprint_;
    job_.exr_files = outputs_.get();
    auto frames_on_disk = [&](std::vector<bool>& on_disk) {
        if (!o_.resume || o_.exr_dir.empty()) return;
        on_disk = sections_on_disk(*outputs_, layouts_, fingerprint_, ctx_->width, ctx_->height);
        drop_interrupted_sections(*outputs_, layouts_, on_disk);
    };
    if (o_.resume && ex_) {  // rank 0 judges, every rank gets its answer
        const int status = share_resume_plan(
            *ex_,
            [&](std::vector<SectionStart>& st, std::vector<bool>& on_disk) {
                st = checkpoints_to_resume(checkpoints_.dir, state_id_, layouts_, ctx_->has_ambient());
                frames_on_disk(on_disk);
            },
            starts_, job_.on_disk);
        if (status != 0) return status;
    } else {
        frames_on_disk(job_.on_disk);
    }
    job_.starts = starts_;
    if (checkpointer_->enabled()) job_.checkpointer = checkpointer_.get();
    int to_render = 0;
    for (int s = 0; s < plan_.sections; ++s) to_render += !done_before(s);
    budget_ = std::make_unique<TimeBudget>(o_.time_limit ? TimeBudget(*o_.time_limit, t0_, to_render) : TimeBudget());
    if (budget_->limited()) job_.budget = budget_.get();
    preview_ = std::make_unique<PreviewSheet>(o_.preview_path, scene_.emission.mode, ctx_->timeline.pulse_buckets,
                                              ctx_->width, ctx_->height, ex_);
    if (preview_->enabled()) job_.preview = preview_.get();
    return 0;
}

// From here on every rank renders, or none does.
int RenderCommand::start_ranks() {
    if (!ex_) return 0;
    const int status = agree_to_start(*ex_, 0, "");
    if (status != 0) return status;
    ranks_started();
    return 0;
}

PipelineStats RenderCommand::render() {
    if (root_) print_render_start(*ctx_, scene_, plan_, ex_);
    setup_seconds_ = since(t0_);
    ProgressBar bar(o_.progress && root_, plan_.sections, scene_.render.passes, scene_.render.alpha);
    for (int s = 0; s < plan_.sections; ++s)
        if (done_before(s)) bar.skip_section(s);
    if (budget_->limited()) bar.set_deadline(*o_.time_limit - since(t0_));
    job_.log = [&](const std::string& line) { if (root_) bar.message(line); };
    job_.section_started = [&](int s, int p) { bar.section_started(s, p); };
    job_.full_pass_seconds = [&](double t, int n) { bar.expect_full_pass(t, n); };
    job_.passes_fixed = [&](int n) { bar.set_passes(n); };
    PipelineStats stats = run_pipeline(job_, *outputs_, [&](int s, int p) { bar.update(s, p); }, interrupted());
    bar.finish();
    if (root_)
        print_after_render(stats, scene_, plan_, o_, *budget_, o_.exr_dir.empty() ? checkpoints_.dir : o_.exr_dir, ex_);
    return stats;
}

double RenderCommand::finish_outputs() {
    const auto tf = Clock::now();
    outputs_->finish();
    return since(tf);
}

void RenderCommand::write_stats(const PipelineStats& stats, double output_seconds) {
    if (o_.stats_path.empty() || !root_) return;
    RunSummary summary;
    summary.scene = &scene_;
    summary.plan = plan_;
    summary.pipeline = stats;
    summary.setup_seconds = setup_seconds_;
    summary.output_seconds = output_seconds;
    summary.exposure = outputs_->exposure().value_or(1.0);
    summary.strategy = o_.strategy;
    summary.threads = o_.threads > 0 ? o_.threads : tbb::info::default_concurrency();
    summary.time_limit = o_.time_limit.value_or(0);
    summary.checkpoint_dir = checkpointer_->enabled() ? checkpoints_.dir : "";
    const Checkpointer::Totals ct = checkpointer_->totals();
    summary.checkpoint_writes = ct.writes;
    summary.checkpoint_bytes = ct.last_bytes;
    summary.checkpoint_seconds = ct.seconds;
    summary.checkpoint_longest = ct.longest;
    summary.preview_writes = preview_->writes();
    summary.wall_seconds = since(t0_);
    write_stats_json(o_.stats_path, summary);
}

// The last lines and the exit status (rank 0 speaks for the job).
int RenderCommand::conclude(const PipelineStats& stats) {
    if (stats.interrupted) {
        if (root_) print_interrupted(stats, plan_, *outputs_, o_, scene_.render.passes, checkpointer_->enabled(), again_);
        return 130;
    }
    checkpointer_->remove_all();  // a finished render needs none of them
    if (!root_) return 0;
    if (stats.steady_black)
        std::fprintf(stderr, "%s\n", steady_black_warning(scene_).c_str());
    print_final_line(*outputs_, o_.stats_path, t0_);
    return 0;
}

}  // namespace

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

// --max-memory bounds what the imports may decode to, checked before they are decoded.
static ImportBudget import_budget(const RunOptions& o) {
    return {o.max_memory_bytes.value_or(0), o.max_memory_bytes ? "--max-memory " + format_bytes(*o.max_memory_bytes) : ""};
}

SceneDesc load_scene(const RunOptions& o) {
    if (!o.scene_path.empty()) refuse_cube_as_scene(o.scene_path);
    SceneDesc scene = o.scene_path.empty()          ? parse_default_scene()
                      : is_model_file(o.scene_path) ? scene_for_model(o.scene_path, o.gltf_light_units, import_budget(o), o.gltf_principled)
                                                    : parse_scene_file(o.scene_path);
    complete_scene(scene, o);
    return scene;
}

void complete_scene(SceneDesc& scene, const RunOptions& o) {
    apply_gltf_light_units(scene, o.gltf_light_units);  // before the files are read
    apply_gltf_principled(scene, o.gltf_principled);
    resolve_imports(scene, import_budget(o));  // meshes, materials, textures and lights of imported files
    apply_overrides(scene, o.overrides);
}

int render_command(RunOptions o, const std::vector<std::string>& argv, const RankSetup& ranks) {
    catch_interrupts(ranks.ex != nullptr);
    RenderCommand run(std::move(o), argv, ranks);
    run.read_and_check();
    run.plan_checkpoints();
    run.open_outputs();
    if (const int status = run.plan_the_run()) return status;
    if (const int status = run.start_ranks()) return status;
    const PipelineStats stats = run.render();
    const double output_seconds = run.finish_outputs();
    run.write_stats(stats, output_seconds);
    return run.conclude(stats);
}

}  // namespace sl
