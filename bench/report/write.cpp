// Writing the report: CSV files, report.md, gnuplot scripts (run if gnuplot is installed) and
// the contact sheets.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "pictures.h"
#include "report.h"
#include "stages/output/png_io.h"
#include "stages/output/tone_map.h"

namespace report {
namespace {

namespace fs = std::filesystem;

// The paper's Table 2 (GPU, its own scene), seconds: frames -> {ours, frame by frame}.
const std::map<int, std::pair<double, double>> kPaper = {
    {1, {79.11, 74.11}},   {4, {78.06, 297.52}},   {8, {81.92, 698.04}},
    {16, {83.59, 1193.08}}, {32, {88.19, 2383.16}}, {48, {98.75, 3571.24}},
};

constexpr double kTargetFlat = 1.15, kTargetSpeedup = 35, kTargetSlope = -1.0 / 3.0;

template <class... A>
std::string fmt(const char* f, A... args) {
    char buf[1024];
    std::snprintf(buf, sizeof buf, f, args...);
    return buf;
}

std::string yes_no(bool b) { return b ? "**met**" : "**not met**"; }

void write_file(const fs::path& p, const std::string& s) {
    std::ofstream out(p, std::ios::binary);
    out << s;
    out.close();
    if (!out) throw std::runtime_error("cannot write " + p.string());
}

struct Fits {
    double slope_raw = NAN, slope_corr = NAN, slope_frames_corr = NAN;
    double slope_indirect_raw = NAN, slope_indirect_corr = NAN;
    int lo = 0, hi = 0;
};

Fits fit(const Report& r) {
    Fits f;
    std::vector<double> x, y_raw, y_corr, y_frames, y_ind_raw, y_ind_corr;
    for (const LadderPoint& p : r.ladder) {
        if (p.strategy != Strategy::Single) continue;
        x.push_back(p.passes);
        y_raw.push_back(p.rmse_steady);
        y_corr.push_back(p.rmse_steady_corr);
        y_frames.push_back(p.rmse_frames_corr);
        y_ind_raw.push_back(p.rmse_indirect);
        y_ind_corr.push_back(p.rmse_indirect_corr);
        f.lo = f.lo == 0 ? p.passes : std::min(f.lo, p.passes);
        f.hi = std::max(f.hi, p.passes);
    }
    f.slope_raw = loglog_slope(x, y_raw);
    f.slope_corr = loglog_slope(x, y_corr);
    f.slope_frames_corr = loglog_slope(x, y_frames);
    f.slope_indirect_raw = loglog_slope(x, y_ind_raw);
    f.slope_indirect_corr = loglog_slope(x, y_ind_corr);
    return f;
}

const Table2Row* row_for(const Report& r, int frames) {
    for (const Table2Row& t : r.table)
        if (t.frames == frames) return &t;
    return nullptr;
}

// ---- CSV ------------------------------------------------------------------------------------

void write_csvs(const Report& r, const fs::path& dir) {
    std::ostringstream c;
    c << "strategy,passes,wall_s,cpu_s,rmse_steady,rmse_steady_ref_noise_removed,rel_rmse_steady,"
         "rmse_frames_mean,rmse_frames_mean_ref_noise_removed,rel_rmse_frames_mean,max_abs_diff_vs_single,"
         "rmse_indirect,rmse_indirect_ref_noise_removed\n";
    for (const LadderPoint& p : r.ladder)
        c << fmt("%s,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%s,%s,%s\n", strategy_name(p.strategy), p.passes, p.wall_s, p.cpu_s,
                 p.rmse_steady,
                 p.rmse_steady_corr, p.rmse_steady / r.ref.mean_steady, p.rmse_frames, p.rmse_frames_corr,
                 p.rmse_frames / r.ref.mean_steady,
                 p.max_diff_vs_single >= 0 ? fmt("%.3g", p.max_diff_vs_single).c_str() : "",
                 p.rmse_indirect >= 0 ? fmt("%.6g", p.rmse_indirect).c_str() : "",
                 p.rmse_indirect_corr >= 0 ? fmt("%.6g", p.rmse_indirect_corr).c_str() : "");
    write_file(dir / "convergence.csv", c.str());

    std::ostringstream fr;
    fr << "strategy,passes,frame,t_begin_ns,t_end_ns,rmse,reference_mean\n";
    for (const LadderPoint& p : r.ladder)
        for (size_t k = 0; k < p.frame_rmse.size(); ++k)
            fr << fmt("%s,%d,%zu,%.6g,%.6g,%.6g,%.6g\n", strategy_name(p.strategy), p.passes, k,
                      r.timeline.edge(static_cast<int64_t>(k)), r.timeline.edge(static_cast<int64_t>(k) + 1),
                      p.frame_rmse[k], mean(r.ref.frames[k]));
    write_file(dir / "frame_rmse.csv", fr.str());

    const Table2Row* one = row_for(r, 1);
    std::ostringstream t;
    t << "frames,ours_s,ours_cpu_s,frame_by_frame_s,frame_by_frame_cpu_s,frame_by_frame_how,"
         "frame_by_frame_lower_bound_s,frame_by_frame_lower_bound_cpu_s,ours_over_ours1,ours_over_ours1_cpu,"
         "fbf_over_ours,fbf_over_ours_cpu,paper_ours_s,paper_fbf_s\n";
    for (const Table2Row& row : r.table) {
        auto paper = kPaper.find(row.frames);
        t << fmt("%d,%.6g,%.6g,%.6g,%.6g,%s,%.6g,%.6g,%s,%s,%.6g,%.6g,%s,%s\n", row.frames, row.ours_s, row.ours_cpu_s,
                 row.fbf_s, row.fbf_cpu_s, row.fbf_full ? "measured" : "lower_bound", row.fbf_lower_s,
                 row.fbf_lower_cpu_s, one ? fmt("%.4f", row.ours_s / one->ours_s).c_str() : "",
                 one ? fmt("%.4f", row.ours_cpu_s / one->ours_cpu_s).c_str() : "", row.fbf_s / row.ours_s,
                 row.fbf_cpu_s / row.ours_cpu_s,
                 paper != kPaper.end() ? fmt("%.2f", paper->second.first).c_str() : "",
                 paper != kPaper.end() ? fmt("%.2f", paper->second.second).c_str() : "");
    }
    write_file(dir / "table2.csv", t.str());

    std::ostringstream ce;
    ce << "what,rays_per_wall_s,fraction_of_bare_embree,rays_per_cpu_s,fraction_of_bare_embree_cpu\n";
    for (auto [what, rate] : {std::pair{"bare_embree", r.ceiling.bare}, std::pair{"photon_pass", r.ceiling.photon_pass},
                              std::pair{"whole_render", r.ceiling.render}})
        ce << fmt("%s,%.6g,%.4f,%.6g,%.4f\n", what, rate.per_wall_s, rate.per_wall_s / r.ceiling.bare.per_wall_s,
                  rate.per_cpu_s, rate.per_cpu_s / r.ceiling.bare.per_cpu_s);
    write_file(dir / "ceiling.csv", ce.str());

    std::ostringstream s;
    s << "threads,render_s,render_speedup,render_cpu_s,bare_embree_rays_per_s,bare_speedup,photon_pass_rays_per_s,"
         "photon_speedup\n";
    const ScalingRow& s1 = r.scaling.front();
    for (const ScalingRow& row : r.scaling)
        s << fmt("%d,%.6g,%.4f,%.6g,%.6g,%.4f,%.6g,%.4f\n", row.threads, row.render_s, s1.render_s / row.render_s,
                 row.render_cpu_s, row.bare.per_wall_s, row.bare.per_wall_s / s1.bare.per_wall_s,
                 row.photon.per_wall_s, row.photon.per_wall_s / s1.photon.per_wall_s);
    write_file(dir / "scaling.csv", s.str());
}

// ---- Markdown -------------------------------------------------------------------------------

std::string markdown(const Report& r, const Fits& f) {
    std::ostringstream m;
    std::time_t now = std::time(nullptr);
    char date[64];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    const Table2Row* one = row_for(r, 1);
    const Table2Row* last = r.table.empty() ? nullptr : &r.table.back();

    m << "# Speed against error: " << r.scene_name << (r.quick ? " (quick run)" : "") << "\n\n";
    m << "Made by `" << r.command << "` on " << date << fmt(" in %.0f s.\n\n", r.total_seconds);
    m << "- Machine: " << r.machine.cpu << ", " << r.machine.cores << " hardware threads; " << r.machine.threads
      << " used. Load average (1/5/15 min) " << r.machine.load_before << " at the start, " << r.machine.load_after
      << " at the end (other work shares this machine: times are noisy).\n";
    m << fmt("- Scene `%s` at %dx%d, %d frames of %.4g ns from %.4g ns, %lld photons per pass, alpha %.4g.\n",
             r.scene_path.c_str(), r.width, r.height, r.frames, r.timeline.delta(), r.timeline.start_ns,
             static_cast<long long>(r.photons), r.alpha);
    m << fmt("- Reference: the average of two single-convergence runs of %d passes with their own seeds "
             "(%.0f s). Their difference gives the reference's own noise (relative RMSE of the steady image "
             "%.3g), which the columns marked \"ref. noise out\" subtract in quadrature.\n",
             r.ref.passes, r.ref.seconds, std::sqrt(r.ref.var_steady) / r.ref.mean_steady);
    m << "- Times are wall seconds from the first pass to the last assembled frame, in process (scene set-up "
         "and file output not counted).\n";
    m << fmt("- No NaN or Inf: %zu non-finite values in %zu images checked.\n\n", r.non_finite, r.images_checked);

    m << "## Targets\n\n";
    if (r.quick)
        m << "**A --quick run: its renders last a few hundredths of a second, too short for timing verdicts. "
             "Run without --quick for the real numbers.**\n\n";
    m << "Judged twice: on wall time, as the paper does, and on the process's CPU time, which other work on "
         "this shared machine disturbs much less (see the load averages above).\n\n";
    m << "| target | measured (wall time) | | measured (CPU time) | |\n|---|---|---|---|---|\n";
    if (one && last && last->frames > 1) {
        double flat = last->ours_s / one->ours_s, flat_cpu = last->ours_cpu_s / one->ours_cpu_s;
        m << fmt("| ours(%d) / ours(1) <= %.2f | %.3f | %s | %.3f | %s |\n", last->frames, kTargetFlat, flat,
                 yes_no(flat <= kTargetFlat).c_str(), flat_cpu, yes_no(flat_cpu <= kTargetFlat).c_str());
        double sp = last->fbf_s / last->ours_s, sp_cpu = last->fbf_cpu_s / last->ours_cpu_s;
        double lo = last->fbf_lower_s / last->ours_s, lo_cpu = last->fbf_lower_cpu_s / last->ours_cpu_s;
        m << fmt("| frame by frame(%d) / ours(%d) >= %.0f | %.1f %s; %.1f at its lower bound | %s | %.1f; %.1f at its "
                 "lower bound | %s |\n",
                 last->frames, last->frames, kTargetSpeedup, sp, last->fbf_full ? "(rendered in full)" : "(lower bound)",
                 lo, yes_no(std::min(sp, lo) >= kTargetSpeedup).c_str(), sp_cpu, lo_cpu,
                 yes_no(std::min(sp_cpu, lo_cpu) >= kTargetSpeedup).c_str());
    }
    const double decades = std::log10(double(f.hi) / f.lo);
    m << fmt("| slope of log RMSE(steady) vs log passes <= -1/3, passes %d..%d (%.1f decades) | %.3f with the "
             "reference's noise taken out; %.3f raw | %s | | |\n",
             f.lo, f.hi, decades, f.slope_corr, f.slope_raw,
             yes_no(f.slope_corr <= kTargetSlope && f.slope_raw <= kTargetSlope && decades >= 1).c_str());
    m << fmt("| (beyond the target) the photon-gathered (indirect) part of the steady image alone, whose PPM "
             "rate is -1/3 | %.3f with the reference's noise taken out; %.3f raw | %s | | |\n",
             f.slope_indirect_corr, f.slope_indirect_raw,
             std::abs(f.slope_indirect_corr - kTargetSlope) <= 0.05 ? "**at PPM's rate**"
             : f.slope_indirect_corr < kTargetSlope                   ? "**faster than PPM's rate**"
                                                                      : "**slower than PPM's rate**");
    m << fmt("| no NaN or Inf in any frame or steady image | %zu in %zu images | %s | | |\n\n", r.non_finite,
             r.images_checked, yes_no(r.non_finite == 0).c_str());

    m << "## Table 2 on this machine\n\n";
    m << fmt("%d passes of %lld photons at %dx%d. Ours is one convergence for all F frames (the best of %d "
             "interleaved rounds). Frame by frame renders every frame as its own full convergence (full photon "
             "paths, as `--strategy frame-by-frame`); \"measured\": all F convergences were rendered and timed, "
             "once; \"lower bound\": F x the fastest one-frame convergence seen (frame by frame is rendered in "
             "full up to F = %d). \"F x fastest\" is that bound for every F: frame by frame cannot cost less. "
             "Wall seconds, and CPU seconds in brackets. The paper's columns are its GPU timings on its own "
             "scene, for the shape only.\n\n",
             r.table_passes, static_cast<long long>(r.photons), r.width, r.height, r.rounds, r.fbf_full_max);
    m << "| frames | ours (s) | frame by frame (s) | how | F x fastest frame (s) | ours(F)/ours(1) | fbf/ours | "
         "paper ours (s) | paper fbf (s) | paper fbf/ours |\n|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|\n";
    for (const Table2Row& row : r.table) {
        auto p = kPaper.find(row.frames);
        m << fmt("| %d | %.2f (%.2f) | %.1f (%.1f) | %s | %.1f (%.1f) | %s | %.1f (%.1f) | %s | %s | %s |\n",
                 row.frames, row.ours_s, row.ours_cpu_s, row.fbf_s, row.fbf_cpu_s,
                 row.fbf_full ? "measured" : "lower bound", row.fbf_lower_s, row.fbf_lower_cpu_s,
                 one ? fmt("%.3f (%.3f)", row.ours_s / one->ours_s, row.ours_cpu_s / one->ours_cpu_s).c_str() : "-",
                 row.fbf_s / row.ours_s, row.fbf_cpu_s / row.ours_cpu_s,
                 p != kPaper.end() ? fmt("%.2f", p->second.first).c_str() : "-",
                 p != kPaper.end() ? fmt("%.2f", p->second.second).c_str() : "-",
                 p != kPaper.end() ? fmt("%.1f", p->second.second / p->second.first).c_str() : "-");
    }
    m << "\n![Table 2](table2.png)\n\n";

    m << "## Error against passes and time\n\n";
    m << "RMSE over all pixels and channels (radiance, W sr^-1 m^-2) against the reference; \"frames\" is the mean "
         "over the frames of each frame's RMSE; \"rel.\" divides by the reference's mean steady radiance "
         << fmt("(%.4g). ", r.ref.mean_steady)
         << "Frame by frame uses the same random streams per pass as single convergence, so its images match "
            "single convergence's at the same passes (last column: largest difference of any pixel value), while "
            "it costs F convergences.\n\n";
    m << "| strategy | passes | wall (s) | CPU (s) | RMSE steady | rel. | ref. noise out | RMSE frames | rel. | "
         "ref. noise out | RMSE indirect | ref. noise out | max abs fbf - single |\n"
         "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const LadderPoint& p : r.ladder)
        m << fmt("| %s | %d | %.2f | %.2f | %.4g | %.4f | %.4g | %.4g | %.4f | %.4g | %s | %s | %s |\n", strategy_name(p.strategy),
                 p.passes, p.wall_s, p.cpu_s, p.rmse_steady, p.rmse_steady / r.ref.mean_steady, p.rmse_steady_corr, p.rmse_frames,
                 p.rmse_frames / r.ref.mean_steady, p.rmse_frames_corr,
                 p.rmse_indirect >= 0 ? fmt("%.4g", p.rmse_indirect).c_str() : "",
                 p.rmse_indirect_corr >= 0 ? fmt("%.4g", p.rmse_indirect_corr).c_str() : "",
                 p.max_diff_vs_single >= 0 ? fmt("%.2g", p.max_diff_vs_single).c_str() : "");
    m << fmt("\nFitted slope of log RMSE against log passes, single convergence, passes %d..%d: steady %.3f "
             "(reference noise out), %.3f (raw); frames %.3f (reference noise out); the photon-gathered part "
             "of the steady image %.3f (reference noise out), %.3f (raw). Progressive photon mapping at "
             "alpha = 2/3 expects -1/3 for what it gathers; direct light and the pixel footprint are plain "
             "Monte Carlo averages (-1/2), and at these settings they carry most of the steady image's error "
             "(mean indirect radiance %.4g of %.4g).\n\n",
             f.lo, f.hi, f.slope_corr, f.slope_raw, f.slope_frames_corr, f.slope_indirect_corr,
             f.slope_indirect_raw, r.ref.mean_indirect, r.ref.mean_steady);
    m << "![RMSE against passes](rmse_vs_passes.png)\n\n![RMSE against wall time](rmse_vs_time.png)\n\n";

    m << "## The measured ceiling\n\n";
    m << "Bare Embree: random rays (origins uniform in the scene's bounds, directions uniform), closest hit, "
         "through the renderer's own BVH, all threads. Photon pass: tracing and the photon grid as the renderer "
         "runs them, rays per second of the pass. Whole render: camera, shadow and photon rays over the wall time "
         "of the fastest Table 2 run at the ladder's frame count.\n\n";
    m << "| | rays per wall second | fraction of bare Embree | rays per CPU second | fraction of bare Embree |\n"
         "|---|---:|---:|---:|---:|\n";
    for (auto [what, rate] : {std::pair{"bare Embree", r.ceiling.bare}, std::pair{"photon pass", r.ceiling.photon_pass},
                              std::pair{"whole render", r.ceiling.render}})
        m << fmt("| %s | %.3g | %.2f | %.3g | %.2f |\n", what, rate.per_wall_s,
                 rate.per_wall_s / r.ceiling.bare.per_wall_s, rate.per_cpu_s, rate.per_cpu_s / r.ceiling.bare.per_cpu_s);
    m << "\n";

    m << "## Thread scaling\n\n";
    m << fmt("Single convergence, %d frames, %d passes (best of %d); bare Embree and photon pass as above. Speed-up "
             "against 1 thread (tbb::global_control). CPU/wall is the process's CPU time over the wall time of "
             "that render: near the thread count when the threads were busy, lower when they waited (for "
             "each other, or for the other work on the machine).\n\n",
             r.frames, r.table_passes, std::max(1, r.rounds / 2));
    m << "| threads | render (s) | speed-up | CPU/wall | bare Embree rays/s | speed-up | photon pass rays/s | speed-up |\n"
         "|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    const ScalingRow& s1 = r.scaling.front();
    for (const ScalingRow& s : r.scaling)
        m << fmt("| %d | %.2f | %.2f | %.2f | %.3g | %.2f | %.3g | %.2f |\n", s.threads, s.render_s,
                 s1.render_s / s.render_s, s.render_cpu_s / s.render_s, s.bare.per_wall_s,
                 s.bare.per_wall_s / s1.bare.per_wall_s, s.photon.per_wall_s, s.photon.per_wall_s / s1.photon.per_wall_s);
    m << "\n## Pictures\n\nThe reference's frames (constant emission: each shows everything that arrived before "
         "the end of its interval):\n\n![contact sheet](contact_sheet.png)\n\n"
         "The steady image along the ladder (single convergence) and the reference:\n\n"
         "![ladder](ladder_sheet.png)\n";
    return m.str();
}

// ---- gnuplot --------------------------------------------------------------------------------

// Paths in the gnuplot scripts are relative to the output folder, where gnuplot is run, so the
// scripts keep working wherever the folder is moved: cd DIR && gnuplot plots/NAME.gp
std::string gp_path(const fs::path& p) {
    std::string s = p.string(), out;
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return "\"" + out + "\"";
}

std::string shell_quote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

void write_plot_data(const Report& r, const fs::path& pd) {
    for (Strategy s : {Strategy::Single, Strategy::FrameByFrame}) {
        std::ostringstream d;
        d << "# passes wall_s rmse_steady rmse_steady_corr rmse_frames rmse_frames_corr rmse_indirect_corr\n";
        for (const LadderPoint& p : r.ladder)
            if (p.strategy == s)
                d << fmt("%d %.6g %.6g %.6g %.6g %.6g %s\n", p.passes, p.wall_s, p.rmse_steady, p.rmse_steady_corr,
                         p.rmse_frames, p.rmse_frames_corr,
                         p.rmse_indirect_corr > 0 ? fmt("%.6g", p.rmse_indirect_corr).c_str() : "?");
        write_file(pd / (s == Strategy::Single ? "conv_single.dat" : "conv_fbf.dat"), d.str());
    }
    const Table2Row* one = row_for(r, 1);
    const Table2Row& base = one ? *one : r.table.front();
    std::ostringstream t;
    t << "# frames ours_s fbf_s fbf_lower_s ours_cpu_s fbf_cpu_s fbf_lower_cpu_s ours_rel_cpu fbf_rel_cpu "
         "paper_ours_rel paper_fbf_rel\n";
    for (const Table2Row& row : r.table) {
        auto p = kPaper.find(row.frames);
        t << fmt("%d %.6g %s %.6g %.6g %s %.6g %.6g %.6g %s %s\n", row.frames, row.ours_s,
                 row.fbf_full ? fmt("%.6g", row.fbf_s).c_str() : "?", row.fbf_lower_s, row.ours_cpu_s,
                 row.fbf_full ? fmt("%.6g", row.fbf_cpu_s).c_str() : "?", row.fbf_lower_cpu_s,
                 row.ours_cpu_s / base.ours_cpu_s, row.fbf_cpu_s / base.ours_cpu_s,
                 p != kPaper.end() ? fmt("%.6g", p->second.first / kPaper.at(1).first).c_str() : "?",
                 p != kPaper.end() ? fmt("%.6g", p->second.second / kPaper.at(1).first).c_str() : "?");
    }
    write_file(pd / "table2.dat", t.str());
}

void write_plot_scripts(const Report& r, const Fits& f, const fs::path& dir, const std::string& terminal) {
    const fs::path pd = "plots";  // relative to dir, where gnuplot runs
    const std::string single = gp_path(pd / "conv_single.dat"), fbf = gp_path(pd / "conv_fbf.dat");
    const std::string head = "set terminal " + terminal + " noenhanced\nset datafile missing \"?\"\nset key top right\n"
                             "set grid\nset logscale xy\n";
    const LadderPoint* first = nullptr;
    for (const LadderPoint& p : r.ladder)
        if (p.strategy == Strategy::Single) { first = &p; break; }
    std::string guide = first ? fmt("guide(x) = %.6g * (x / %d.0) ** (-1.0/3)\n", first->rmse_steady_corr, first->passes)
                              : "guide(x) = NaN\n";
    std::ostringstream a;
    a << head << "set output " << gp_path("rmse_vs_passes.png") << "\n"
      << fmt("set title \"%s, %dx%d, %d frames, %lld photons/pass: RMSE against passes (slopes: steady %.3f, "
             "photon-gathered part %.3f)\"\n",
             r.scene_name.c_str(), r.width, r.height, r.frames, static_cast<long long>(r.photons), f.slope_corr,
             f.slope_indirect_corr)
      << "set xlabel \"passes\"\nset ylabel \"RMSE against the reference (W sr^-1 m^-2)\"\n" << guide
      << "plot " << single << " using 1:4 with linespoints lw 2 pt 7 title \"single: steady\", \\\n"
      << "     " << single << " using 1:6 with linespoints lw 2 pt 5 title \"single: frames (mean)\", \\\n"
      << "     " << fbf << " using 1:4 with points pt 6 ps 2 title \"frame by frame: steady\", \\\n"
      << "     " << fbf << " using 1:6 with points pt 4 ps 2 title \"frame by frame: frames (mean)\", \\\n"
      << "     " << single << " using 1:3 with lines dt 2 lc rgb \"gray\" title \"single: steady, raw (reference noise in)\", \\\n"
      << "     " << single << " using 1:7 with linespoints lw 2 pt 9 title \"single: photon-gathered part of steady\", \\\n"
      << "     guide(x) with lines dt 3 lc rgb \"black\" title \"passes^(-1/3)\"\n";
    write_file(dir / pd / "rmse_vs_passes.gp", a.str());

    std::ostringstream b;
    b << head << "set output " << gp_path("rmse_vs_time.png") << "\n"
      << fmt("set title \"%s, %dx%d, %d frames: RMSE against wall time (%d threads)\"\n", r.scene_name.c_str(),
             r.width, r.height, r.frames, r.machine.threads)
      << "set xlabel \"wall time (s)\"\nset ylabel \"RMSE against the reference (W sr^-1 m^-2)\"\n"
      << "plot " << single << " using 2:4 with linespoints lw 2 pt 7 title \"single: steady\", \\\n"
      << "     " << single << " using 2:6 with linespoints lw 2 pt 5 title \"single: frames (mean)\", \\\n"
      << "     " << fbf << " using 2:4 with linespoints lw 2 pt 6 title \"frame by frame: steady\", \\\n"
      << "     " << fbf << " using 2:6 with linespoints lw 2 pt 4 title \"frame by frame: frames (mean)\"\n";
    write_file(dir / pd / "rmse_vs_time.gp", b.str());

    const std::string t = gp_path(pd / "table2.dat");
    std::ostringstream c;
    c << "set terminal " << terminal << " noenhanced\nset datafile missing \"?\"\nset output " << gp_path("table2.png") << "\n"
      << "set multiplot layout 1,2 title "
      << fmt("\"Table 2 on this machine: %s, %dx%d, %d passes x %lld photons\"\n", r.scene_name.c_str(), r.width,
             r.height, r.table_passes, static_cast<long long>(r.photons))
      << "set grid\nset logscale y\nset key top left\nset xlabel \"frames F\"\nset xrange [0:*]\n"
      << "set ylabel \"seconds\"\nset title \"time to render F frames (solid: wall, dashed: CPU)\"\n"
      << "plot " << t << " using 1:2 with linespoints lw 2 pt 7 lc 1 title \"ours (one convergence)\", \\\n"
      << "     " << t << " using 1:3 with linespoints lw 2 pt 5 lc 2 title \"frame by frame, measured\", \\\n"
      << "     " << t << " using 1:4 with lines dt 3 lw 2 lc 3 title \"frame by frame, F x fastest frame\", \\\n"
      << "     " << t << " using 1:5 with linespoints dt 2 pt 6 lc 1 notitle, \\\n"
      << "     " << t << " using 1:6 with linespoints dt 2 pt 4 lc 2 notitle\n"
      << "set ylabel \"CPU time / ours(1)\"\nset title \"relative to one frame (CPU time), against the paper\"\n"
      << "plot " << t << " using 1:8 with linespoints lw 2 pt 7 lc 1 title \"ours\", \\\n"
      << "     " << t << " using 1:9 with linespoints lw 2 pt 5 lc 2 title \"frame by frame\", \\\n"
      << "     " << t << " using 1:10 with linespoints dt 2 pt 6 lc 1 title \"paper: ours\", \\\n"
      << "     " << t << " using 1:11 with linespoints dt 2 pt 4 lc 2 title \"paper: frame by frame\"\n"
      << "unset multiplot\n";
    write_file(dir / pd / "table2.gp", c.str());
}

// Runs gnuplot on every script; returns a note for the report (empty when all went well).
std::string run_gnuplot(const Report& r, const Fits& f, const fs::path& dir) {
    // pngcairo draws nicer text; the plain png terminal (libgd) is the fallback.
    std::string terminal = "pngcairo size 1000,640 font \"DejaVu Sans,10\"";
    if (std::system("gnuplot -e 'set terminal pngcairo' > /dev/null 2>&1") != 0) {
        if (std::system("gnuplot -e 'set terminal png' > /dev/null 2>&1") != 0)
            return "gnuplot is not installed (apt-get install gnuplot-nox): the plots were not drawn; their "
                   "scripts are in plots/";
        terminal = "png size 1000,640";
    }
    write_plot_scripts(r, f, dir, terminal);
    std::string failed;
    for (const char* s : {"rmse_vs_passes.gp", "rmse_vs_time.gp", "table2.gp"}) {
        std::string cmd = "cd " + shell_quote(dir.string()) + " && gnuplot plots/" + s + " > plots/" + s + ".log 2>&1";
        if (std::system(cmd.c_str()) != 0) failed += std::string(failed.empty() ? "" : ", ") + s;
    }
    return failed.empty() ? "" : "gnuplot failed on " + failed + " (see plots/*.log)";
}

// ---- pictures -------------------------------------------------------------------------------

void write_canvas(const fs::path& p, const Canvas& c) { sl::write_png(p.string(), c.width, c.height, c.rgb.data()); }

void write_sheets(const Report& r, const fs::path& dir) {
    const double exposure = sl::exposure_from_steady(r.ref.steady.data(), r.width, r.height);
    // Enough decimals to tell neighbouring frame edges apart.
    const int digits = std::clamp(static_cast<int>(std::ceil(-std::log10(r.timeline.delta()))) + 1, 0, 6);
    std::vector<Tile> tiles;
    for (size_t k = 0; k < r.ref.frames.size(); ++k) {
        const double a = r.timeline.edge(static_cast<int64_t>(k)), b = r.timeline.edge(static_cast<int64_t>(k) + 1);
        tiles.push_back({&r.ref.frames[k], fmt("%.*f-%.*f ns", digits, a, digits, b)});
    }
    // About 1.5 times as many columns as rows, and full rows where a divisor allows it.
    const int n = static_cast<int>(tiles.size());
    int columns = static_cast<int>(std::ceil(std::sqrt(n * 1.5)));
    for (int c = columns; c >= static_cast<int>(std::ceil(std::sqrt(double(n)))); --c)
        if (n % c == 0) {
            columns = c;
            break;
        }
    write_canvas(dir / "contact_sheet.png",
                 contact_sheet(tiles, r.width, r.height, exposure, columns,
                               fmt("%s: %d frames, reference (2x%d passes)", r.scene_name.c_str(), r.frames,
                                   r.ref.passes)));

    std::vector<Tile> ladder;
    for (size_t i = 0; i < r.steady_by_passes.size(); ++i)
        ladder.push_back({&r.steady_by_passes[i].second,
                          fmt("%d passes %.2fs", r.steady_by_passes[i].first, r.steady_wall_s[i])});
    ladder.push_back({&r.ref.steady, fmt("reference 2x%d", r.ref.passes)});
    write_canvas(dir / "ladder_sheet.png",
                 contact_sheet(ladder, r.width, r.height, exposure, std::min<int>(ladder.size(), 5),
                               "steady image along the ladder"));
}

}  // namespace

double loglog_slope(const std::vector<double>& x, const std::vector<double>& y) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    for (size_t i = 0; i < x.size() && i < y.size(); ++i) {
        if (!(x[i] > 0 && y[i] > 0)) continue;
        double lx = std::log(x[i]), ly = std::log(y[i]);
        sx += lx; sy += ly; sxx += lx * lx; sxy += lx * ly;
        ++n;
    }
    double d = n * sxx - sx * sx;
    return n < 2 || d == 0 ? NAN : (n * sxy - sx * sy) / d;
}

void write_everything(const Report& r, const fs::path& dir, bool plots) {
    fs::create_directories(dir / "plots");
    const Fits f = fit(r);
    write_csvs(r, dir);
    write_plot_data(r, dir / "plots");
    write_sheets(r, dir);
    std::string md = markdown(r, f);
    if (plots) {
        std::string note = run_gnuplot(r, f, dir);
        if (!note.empty()) {
            md += "\n> Note: " + note + "\n";
            std::fprintf(stderr, "bench_report: %s\n", note.c_str());
        }
    } else {
        write_plot_scripts(r, f, dir, "pngcairo size 1000,640");
        md += "\n> Plots were not drawn (--no-plots); run gnuplot on plots/*.gp.\n";
    }
    write_file(dir / "report.md", md);
}

}  // namespace report
