// bench_report: speed against error, in numbers and pictures (issue 5).
//
//   ./build/bench_report [--scene samples/cornell_box.json] [--out bench/results] [--quick] ...
//
// See usage() below (or --help) for every option and what is written.
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "config/parse_scene.h"
#include "foundation/errors.h"
#include "report.h"

namespace report {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const char* kUsage = R"(bench_report: speed against error for slowlight, in numbers and pictures.

usage: bench_report [--scene FILE.json] [--out DIR] [--quick] [options]

On one scene it renders, in process (no files are read back, nothing but the report written):
  1. a reference: two long single-convergence runs with other seeds, averaged (their
     difference measures the reference's own noise, which is then taken out of the errors);
  2. a ladder of shorter runs (passes 2, 4, ..., 256) with single convergence and with frame by
     frame, and the RMSE against the reference of the steady image and of every frame (mean
     over frames), against passes and against wall time; the fitted slope of log RMSE(steady)
     against log passes;
  3. the paper's Table 2 on this machine: time to render F = 1, 4, 8, 16, 32, 48 frames, ours
     (one convergence) against frame by frame (one full convergence per frame);
  4. the measured ceiling: bare Embree rays/s on the same scene and threads against the
     renderer's photon pass and whole render; and thread scaling from 1 to all threads;
  5. pictures: RMSE plots and Table 2 (through gnuplot, if installed), a contact sheet of the
     reference's frames with their times, and the steady image along the ladder.

Times are wall seconds from the first pass to the last assembled frame (the scene's BVH is
built beforehand and not counted, no files are written), and beside them the process's CPU
seconds over the same span, which other work on a shared machine disturbs much less. Every
time in Table 2 is the best of --rounds interleaved rounds. Takes about 7-8 minutes on a
2-core machine (longer when other work shares it); --quick well under a minute.

options:
  --scene FILE       scene (default: samples/cornell_box.json of the source tree)
  --out DIR          where to write (default: bench/results; with --quick: bench/results/quick)
  --quick            a small, fast run (under a minute): 64x64, few photons and passes
  --width W --height H        image size (default 128x128)
  --frames F         frames for the ladder and the contact sheet (default: the scene's)
  --photons N        photons per pass (default 50000)
  --ladder A,B,...   passes of the shorter runs (default 2,4,8,16,32,64,128,256)
  --fbf-ladder-max N frame by frame only for ladder passes <= N (default 16)
  --ref-passes N     passes of each of the two reference runs (default 768)
  --table-passes N   passes for Table 2, the ceiling and scaling (default 16)
  --table-frames A,B,...      frame counts of Table 2 (default 1,4,8,16,32,48)
  --fbf-full-max F   render frame by frame in full up to F frames; above it, time F x the
                     fastest single-frame convergence measured (default 48: all in full)
  --rounds N         interleaved rounds for Table 2 timings (default 5)
  --alpha A          PPM alpha for every run (default 0.6667, as in the -1/3 rate; 'scene'
                     keeps the scene's value)
  --seed N           seed of the ladder runs (default 1; the references use others)
  --threads N        threads (default: all); scaling goes from 1 to N
  --no-plots         do not run gnuplot (the .gp scripts and data are still written)
  -h, --help         this text

writes into DIR:
  report.md          every table below, the targets and whether they are met
  convergence.csv    strategy, passes, wall time, RMSE (steady, mean over frames), ...
  frame_rmse.csv     RMSE of every frame for every ladder run
  table2.csv         Table 2: frames, ours, frame by frame, ratios
  ceiling.csv        rays/s: bare Embree, photon pass, whole render
  scaling.csv        threads against time and rays/s
  rmse_vs_passes.png rmse_vs_time.png table2.png   (gnuplot; scripts in plots/)
  contact_sheet.png  the reference's frames with their time intervals
  ladder_sheet.png   the steady image at every ladder step and the reference
)";

// ---- options --------------------------------------------------------------------------------

struct Options {
    std::string scene = std::string(SLOWLIGHT_SOURCE_DIR) + "/samples/cornell_box.json";
    std::string out;
    bool quick = false;
    int width = 128, height = 128, frames = 0;
    int64_t photons = 50000;
    std::vector<int> ladder{2, 4, 8, 16, 32, 64, 128, 256};
    int fbf_ladder_max = 16;
    int ref_passes = 768;
    int table_passes = 16;
    std::vector<int> table_frames{1, 4, 8, 16, 32, 48};
    int fbf_full_max = 48;
    int rounds = 5;
    double alpha = 2.0 / 3.0;  // <= 0: the scene's
    uint64_t seed = 1;
    int threads = 0;
    bool plots = true;
};

[[noreturn]] void bad(const std::string& msg) {
    std::fprintf(stderr, "error: bench_report: %s (see --help)\n", msg.c_str());
    std::exit(2);
}

long long to_int(const std::string& opt, const std::string& v, long long lo, long long hi) {
    char* end = nullptr;
    errno = 0;
    long long x = std::strtoll(v.c_str(), &end, 10);
    if (v.empty() || *end || errno || x < lo || x > hi)
        bad(opt + ": expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got '" + v + "'");
    return x;
}

std::vector<int> to_list(const std::string& opt, const std::string& v, int lo, int hi) {
    std::vector<int> out;
    std::stringstream ss(v);
    std::string item;
    while (std::getline(ss, item, ',')) out.push_back(static_cast<int>(to_int(opt, item, lo, hi)));
    if (out.empty()) bad(opt + ": empty list");
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

Options parse_options(int argc, char** argv) {
    Options o;
    // --quick first, so that explicit options given with it still win.
    for (int i = 1; i < argc; ++i)
        if (!std::strcmp(argv[i], "--quick")) {
            o.quick = true;
            o.width = o.height = 64;
            o.photons = 5000;
            o.ladder = {1, 2, 4, 8, 16, 32};
            o.fbf_ladder_max = 4;
            o.ref_passes = 192;
            o.table_passes = 4;
            o.fbf_full_max = 8;
            o.rounds = 2;
        }
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) bad(a + ": needs a value");
            return argv[++i];
        };
        if (a == "-h" || a == "--help") {
            std::fputs(kUsage, stdout);
            std::exit(0);
        } else if (a == "--quick") {
        } else if (a == "--scene") o.scene = value();
        else if (a == "--out") o.out = value();
        else if (a == "--width") o.width = static_cast<int>(to_int(a, value(), 8, 8192));
        else if (a == "--height") o.height = static_cast<int>(to_int(a, value(), 8, 8192));
        else if (a == "--frames") o.frames = static_cast<int>(to_int(a, value(), 1, 100000));
        else if (a == "--photons") o.photons = to_int(a, value(), 1, 1000000000);
        else if (a == "--ladder") o.ladder = to_list(a, value(), 1, 1000000);
        else if (a == "--fbf-ladder-max") o.fbf_ladder_max = static_cast<int>(to_int(a, value(), 0, 1000000));
        else if (a == "--ref-passes") o.ref_passes = static_cast<int>(to_int(a, value(), 1, 10000000));
        else if (a == "--table-passes") o.table_passes = static_cast<int>(to_int(a, value(), 1, 1000000));
        else if (a == "--table-frames") o.table_frames = to_list(a, value(), 1, 100000);
        else if (a == "--fbf-full-max") o.fbf_full_max = static_cast<int>(to_int(a, value(), 0, 100000));
        else if (a == "--rounds") o.rounds = static_cast<int>(to_int(a, value(), 1, 1000));
        else if (a == "--alpha") {
            std::string v = value();
            if (v == "scene") o.alpha = 0;
            else {
                char* end = nullptr;
                o.alpha = std::strtod(v.c_str(), &end);
                if (*end || !(o.alpha > 0 && o.alpha < 1)) bad("--alpha: expected a number in (0, 1) or 'scene'");
            }
        } else if (a == "--seed") o.seed = static_cast<uint64_t>(to_int(a, value(), 0, std::numeric_limits<long long>::max()));
        else if (a == "--threads") o.threads = static_cast<int>(to_int(a, value(), 1, 4096));
        else if (a == "--no-plots") o.plots = false;
        else bad("unknown option '" + a + "'");
    }
    if (o.out.empty()) o.out = o.quick ? "bench/results/quick" : "bench/results";
    if (o.threads == 0) o.threads = tbb::info::default_concurrency();
    return o;
}

// ---- small helpers --------------------------------------------------------------------------

Clock::time_point g_start = Clock::now();
double elapsed() { return std::chrono::duration<double>(Clock::now() - g_start).count(); }

void progress(const char* fmt, auto... args) {
    std::fprintf(stderr, "[%6.1f s] ", elapsed());
    std::fprintf(stderr, fmt, args...);
    std::fputc('\n', stderr);
}

std::string read_first_line_with(const std::string& path, const std::string& key) {
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line))
        if (line.rfind(key, 0) == 0) {
            auto p = line.find(':');
            std::string v = p == std::string::npos ? line : line.substr(p + 1);
            v.erase(0, v.find_first_not_of(" \t"));
            return v;
        }
    return "unknown";
}

std::string load_average() {
    std::ifstream in("/proc/loadavg");
    std::string a, b, c;
    in >> a >> b >> c;
    return a.empty() ? "unknown" : a + " " + b + " " + c;
}

sl::RenderContext* make_context(std::vector<std::unique_ptr<sl::RenderContext>>& keep, sl::SceneDesc s, int frames) {
    s.time.frames = frames;
    if (s.emission.mode == sl::EmissionMode::Pulse) {  // a pulse of one frame at any F
        s.emission.width_ns = 0;
        s.emission.width_frames = 1;
    }
    keep.push_back(std::make_unique<sl::RenderContext>(s));
    return keep.back().get();
}

}  // namespace
}  // namespace report

int main(int argc, char** argv) {
    using namespace report;
    Options o = parse_options(argc, argv);
    const fs::path out_dir = o.out;
    tbb::global_control threads_limit(tbb::global_control::max_allowed_parallelism, o.threads);

    sl::SceneDesc scene;
    try {
        scene = sl::parse_scene_file(o.scene);
        fs::create_directories(out_dir / "plots");
    } catch (const sl::InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: bench_report: %s\n", e.what());
        return 1;
    }
    scene.camera.width = o.width;
    scene.camera.height = o.height;
    scene.render.photons_per_pass = o.photons;
    if (o.alpha > 0) scene.render.alpha = static_cast<float>(o.alpha);
    const int frames = o.frames > 0 ? o.frames : scene.time.frames;

    Report rep;
    rep.quick = o.quick;
    rep.scene_name = fs::path(o.scene).stem().string();
    rep.scene_path = o.scene;  // shown relative to the source tree when inside it
    const std::string src = std::string(SLOWLIGHT_SOURCE_DIR) + "/";
    if (rep.scene_path.rfind(src, 0) == 0) rep.scene_path.erase(0, src.size());
    rep.width = o.width;
    rep.height = o.height;
    rep.frames = frames;
    rep.photons = o.photons;
    rep.alpha = scene.render.alpha;
    rep.table_passes = o.table_passes;
    rep.rounds = o.rounds;
    rep.fbf_full_max = o.fbf_full_max;
    rep.fbf_ladder_max = o.fbf_ladder_max;
    rep.command = "./build/bench_report";
    for (int i = 1; i < argc; ++i) rep.command += " " + std::string(argv[i]);
    rep.machine.cpu = read_first_line_with("/proc/cpuinfo", "model name");
    rep.machine.cores = static_cast<int>(std::thread::hardware_concurrency());
    rep.machine.threads = o.threads;
    rep.machine.load_before = load_average();

    std::vector<std::unique_ptr<sl::RenderContext>> contexts;
    auto context = [&](int f, uint64_t seed) {
        sl::SceneDesc s = scene;
        s.render.seed = seed;
        return make_context(contexts, s, f);
    };
    auto direct_context = [&](int f, uint64_t seed) {
        sl::SceneDesc s = scene;
        s.render.seed = seed;
        s.render.max_depth = 1;
        return make_context(contexts, s, f);
    };
    auto minus = [](const Image& x, const Image& y) {
        Image d(x.size());
        for (size_t i = 0; i < x.size(); ++i) d[i] = x[i] - y[i];
        return d;
    };
    std::map<int, sl::RenderContext*> ctx_for;  // frames -> context with the ladder's seed
    for (int f : o.table_frames) ctx_for[f] = context(f, o.seed);
    if (!ctx_for.count(frames)) ctx_for[frames] = context(frames, o.seed);
    const sl::RenderContext& ladder_ctx = *ctx_for[frames];
    rep.timeline = ladder_ctx.timeline;
    progress("%s: %dx%d, %d frames, %lld photons/pass, alpha %.4g, %d threads; writing to %s",
             rep.scene_name.c_str(), o.width, o.height, frames, static_cast<long long>(o.photons), rep.alpha,
             o.threads, out_dir.string().c_str());

    auto check = [&](const RunResult& r) {  // every image of every run: no NaN, no Inf
        for (const Image& f : r.frames) rep.non_finite += count_non_finite(f), ++rep.images_checked;
        rep.non_finite += count_non_finite(r.steady), ++rep.images_checked;
    };

    // 1. The reference: two long runs with their own seeds, averaged.
    {
        RunResult a = render(*context(frames, o.seed + 1000003), Strategy::Single, o.ref_passes, o.photons);
        progress("reference A: %d passes in %.1f s", o.ref_passes, a.wall_s);
        RunResult b = render(*context(frames, o.seed + 2000003), Strategy::Single, o.ref_passes, o.photons);
        progress("reference B: %d passes in %.1f s", o.ref_passes, b.wall_s);
        check(a);
        check(b);
        auto average = [](const Image& x, const Image& y) {
            Image m(x.size());
            for (size_t i = 0; i < x.size(); ++i) m[i] = 0.5f * (x[i] + y[i]);
            return m;
        };
        Reference& ref = rep.ref;
        ref.passes = o.ref_passes;
        ref.seconds = a.wall_s + b.wall_s;
        ref.steady = average(a.steady, b.steady);
        ref.var_steady = std::pow(rmse(a.steady, b.steady), 2) / 4;  // Var(mean of 2) = RMSE(a,b)^2 / 4
        for (int f = 0; f < frames; ++f) {
            ref.frames.push_back(average(a.frames[f], b.frames[f]));
            ref.var_frames.push_back(std::pow(rmse(a.frames[f], b.frames[f]), 2) / 4);
        }
        ref.mean_steady = mean(ref.steady);
        // Direct-only twins (max_depth 1, same seeds): their difference from A and B is the
        // photon-gathered part alone, whose error shows progressive photon mapping's own rate.
        RunResult ad = render(*direct_context(frames, o.seed + 1000003), Strategy::Single, o.ref_passes, o.photons);
        RunResult bd = render(*direct_context(frames, o.seed + 2000003), Strategy::Single, o.ref_passes, o.photons);
        progress("direct-only twins of the references: %.1f s", ad.wall_s + bd.wall_s);
        Image ia = minus(a.steady, ad.steady), ib = minus(b.steady, bd.steady);
        ref.indirect = average(ia, ib);
        ref.var_indirect = std::pow(rmse(ia, ib), 2) / 4;
        ref.mean_indirect = mean(ref.indirect);
    }
    const Reference& ref = rep.ref;

    // 2. The ladder: single convergence at every step, frame by frame at the lower ones.
    auto score = [&](const RunResult& r, Strategy s) {
        LadderPoint p;
        p.strategy = s;
        p.passes = r.passes;
        p.wall_s = r.wall_s;
        p.cpu_s = r.cpu_s;
        p.rmse_steady = rmse(r.steady, ref.steady);
        p.rmse_steady_corr = std::sqrt(std::max(0.0, p.rmse_steady * p.rmse_steady - ref.var_steady));
        double sum = 0, sum_corr = 0;
        for (int f = 0; f < frames; ++f) {
            double e = rmse(r.frames[f], ref.frames[f]);
            p.frame_rmse.push_back(e);
            sum += e;
            sum_corr += std::sqrt(std::max(0.0, e * e - ref.var_frames[f]));
        }
        p.rmse_frames = sum / frames;
        p.rmse_frames_corr = sum_corr / frames;
        return p;
    };
    std::map<int, RunResult> single_runs;  // kept for the comparison with frame by frame
    const sl::RenderContext& direct_ctx = *direct_context(frames, o.seed);
    for (int n : o.ladder) {
        RunResult r = render(ladder_ctx, Strategy::Single, n, o.photons);
        check(r);
        rep.ladder.push_back(score(r, Strategy::Single));
        {
            RunResult d = render(direct_ctx, Strategy::Single, n, o.photons, false);
            LadderPoint& p = rep.ladder.back();
            p.rmse_indirect = rmse(minus(r.steady, d.steady), ref.indirect);
            p.rmse_indirect_corr = std::sqrt(std::max(0.0, p.rmse_indirect * p.rmse_indirect - ref.var_indirect));
        }
        progress("single, %d passes: %.2f s, RMSE steady %.4g, frames %.4g", n, r.wall_s,
                 rep.ladder.back().rmse_steady, rep.ladder.back().rmse_frames);
        rep.steady_by_passes.emplace_back(n, r.steady);
        rep.steady_wall_s.push_back(r.wall_s);
        if (n <= o.fbf_ladder_max) single_runs[n] = std::move(r);
    }
    RunResult fbf_ladder_at_table;  // frame by frame at (frames, table passes), if the ladder ran it
    for (int n : o.ladder) {
        if (n > o.fbf_ladder_max) continue;
        RunResult r = render(ladder_ctx, Strategy::FrameByFrame, n, o.photons);
        check(r);
        LadderPoint p = score(r, Strategy::FrameByFrame);
        const RunResult& s = single_runs[n];
        double d = 0;
        for (int f = 0; f < frames; ++f)
            for (size_t i = 0; i < s.frames[f].size(); ++i)
                d = std::max(d, std::abs(double(s.frames[f][i]) - r.frames[f][i]));
        p.max_diff_vs_single = d;
        rep.ladder.push_back(p);
        progress("frame by frame, %d passes: %.2f s, RMSE steady %.4g, frames %.4g (max |fbf - single| %.3g)", n,
                 r.wall_s, p.rmse_steady, p.rmse_frames, d);
        if (n == o.table_passes) {
            fbf_ladder_at_table = r;
            fbf_ladder_at_table.frames.clear();
        }
        single_runs.erase(n);
    }

    // 3. Table 2: ours as the best of interleaved rounds; frame by frame in full, once per F.
    for (int f : o.table_frames) rep.table.push_back(Table2Row{f});
    auto best = [](double& slot, double v) { slot = slot == 0 ? v : std::min(slot, v); };
    for (int round = 0; round < o.rounds; ++round) {
        for (Table2Row& row : rep.table) {
            RunResult r = render(*ctx_for[row.frames], Strategy::Single, o.table_passes, o.photons, false);
            check(r);
            if (row.ours_s == 0 || r.wall_s < row.ours_s) {
                row.camera_s = r.camera_s;
                row.photons_s = r.photons_s;
                row.gather_s = r.gather_s;
                row.assembly_s = r.assembly_s;
            }
            best(row.ours_s, r.wall_s);
            best(row.ours_cpu_s, r.cpu_s);
            row.ours_rays = static_cast<double>(r.camera_rays + r.photon_rays);
        }
        const Table2Row &a = rep.table.front(), &b = rep.table.back();
        progress("Table 2, round %d/%d: ours(%d) %.2f s (CPU %.2f s; camera %.2f, photons %.2f, gather %.2f, "
                 "frames %.3f) ... ours(%d) %.2f s (CPU %.2f s; camera %.2f, photons %.2f, gather %.2f, frames %.3f)",
                 round + 1, o.rounds, a.frames, a.ours_s, a.ours_cpu_s, a.camera_s, a.photons_s, a.gather_s,
                 a.assembly_s, b.frames, b.ours_s, b.ours_cpu_s, b.camera_s, b.photons_s, b.gather_s, b.assembly_s);
    }
    // Every frame of frame by frame is one full convergence, so F x the fastest such
    // convergence seen is a lower bound of its time, whatever the load on the machine.
    double fastest = 0, fastest_cpu = 0;
    auto note_sections = [&](const RunResult& r) {
        for (double s : r.section_s) best(fastest, s);
        for (double s : r.section_cpu_s) best(fastest_cpu, s);
    };
    if (fbf_ladder_at_table.passes > 0) note_sections(fbf_ladder_at_table);
    for (Table2Row& row : rep.table) {
        if (row.frames > o.fbf_full_max) continue;
        row.fbf_full = true;
        RunResult r;
        if (row.frames == frames && fbf_ladder_at_table.passes > 0) {
            r = fbf_ladder_at_table;  // the ladder rendered it already
        } else {
            r = render(*ctx_for[row.frames], Strategy::FrameByFrame, o.table_passes, o.photons, false);
            check(r);
            note_sections(r);
            progress("Table 2, frame by frame, %d frames: %.1f s (CPU %.1f s)", row.frames, r.wall_s, r.cpu_s);
        }
        row.fbf_s = r.wall_s;
        row.fbf_cpu_s = r.cpu_s;
    }
    if (fastest == 0) {  // nothing was rendered frame by frame: time one-frame convergences now
        for (int round = 0; round < o.rounds; ++round)
            note_sections(render(*ctx_for[rep.table.front().frames], Strategy::FrameByFrame, o.table_passes,
                                 o.photons, false));
    }
    for (Table2Row& row : rep.table) {
        row.fbf_lower_s = row.frames * fastest;
        row.fbf_lower_cpu_s = row.frames * fastest_cpu;
        if (!row.fbf_full) {
            row.fbf_s = row.fbf_lower_s;
            row.fbf_cpu_s = row.fbf_lower_cpu_s;
        }
    }

    // 4. The ceiling and thread scaling.
    const size_t bare_rays = o.quick ? (size_t(1) << 19) : (size_t(1) << 22);
    const int photon_passes = o.quick ? 2 : 8;
    rep.ceiling.bare = bare_embree_rays_per_s(ladder_ctx, bare_rays, 3);
    rep.ceiling.photon_pass = photon_pass_rays_per_s(ladder_ctx, photon_passes, o.photons, 3);
    for (const Table2Row& row : rep.table)
        if (row.frames == frames || (&row == &rep.table.back() && rep.ceiling.render.per_wall_s == 0))
            rep.ceiling.render = {row.ours_rays / row.ours_s, row.ours_rays / row.ours_cpu_s};
    progress("ceiling, rays/s of wall time: bare Embree %.3g, photon pass %.3g, whole render %.3g",
             rep.ceiling.bare.per_wall_s, rep.ceiling.photon_pass.per_wall_s, rep.ceiling.render.per_wall_s);
    std::vector<int> thread_counts;
    for (int t = 1; t < o.threads; t *= 2) thread_counts.push_back(t);
    thread_counts.push_back(o.threads);
    for (int t : thread_counts) {
        ScalingRow row;
        row.threads = t;
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, t);
        for (int round = 0; round < std::max(1, o.rounds / 2); ++round) {
            RunResult r = render(ladder_ctx, Strategy::Single, o.table_passes, o.photons, false);
            if (row.render_s == 0 || r.wall_s < row.render_s) {
                row.render_s = r.wall_s;
                row.render_cpu_s = r.cpu_s;
            }
        }
        row.bare = bare_embree_rays_per_s(ladder_ctx, bare_rays, 2);
        row.photon = photon_pass_rays_per_s(ladder_ctx, photon_passes, o.photons, 2);
        rep.scaling.push_back(row);
        progress("%d thread(s): render %.2f s (CPU %.2f s), bare Embree %.3g rays/s, photon pass %.3g rays/s", t,
                 row.render_s, row.render_cpu_s, row.bare.per_wall_s, row.photon.per_wall_s);
    }
    rep.machine.load_after = load_average();
    rep.total_seconds = elapsed();

    // 5. Tables, plots and pictures.
    try {
        write_everything(rep, out_dir, o.plots);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: bench_report: %s\n", e.what());
        return 1;
    }
    progress("done: %s", (out_dir / "report.md").string().c_str());
    if (rep.non_finite) {
        std::fprintf(stderr, "error: bench_report: %zu non-finite pixel values in the renders\n", rep.non_finite);
        return 1;
    }
    return 0;
}
