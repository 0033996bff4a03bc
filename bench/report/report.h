#pragma once
// The report's numbers, and writing them out: CSV, Markdown, gnuplot plots, contact sheets.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "foundation/timeline.h"
#include "runs.h"

namespace report {

struct Machine {
    std::string cpu;
    int cores = 0, threads = 0;
    std::string load_before, load_after;  // /proc/loadavg at the start and the end
};

// The average of two long runs with other seeds; var_* is the variance of that average per
// pixel value (RMSE(a, b)^2 / 4), which the errors below have taken out where marked.
struct Reference {
    int passes = 0;
    double seconds = 0;
    Image steady;
    std::vector<Image> frames;
    double var_steady = 0;
    std::vector<double> var_frames;
    double mean_steady = 0;
    // The photon-gathered (indirect) part of the steady image: the render minus a direct-only
    // render (max_depth 1) with the same seed, whose camera pass is the same sample for sample.
    Image indirect;
    double var_indirect = 0, mean_indirect = 0;
};

struct LadderPoint {
    Strategy strategy = Strategy::Single;
    int passes = 0;
    double wall_s = 0, cpu_s = 0;
    double rmse_steady = 0, rmse_steady_corr = 0;  // corr: the reference's own noise taken out
    double rmse_frames = 0, rmse_frames_corr = 0;  // mean over frames
    double rmse_indirect = -1, rmse_indirect_corr = -1;  // single convergence only
    std::vector<double> frame_rmse;
    double max_diff_vs_single = -1;  // frame by frame: largest |fbf - single| at the same passes
};

// Every time twice: wall seconds, and CPU seconds of the process (user + system), which other
// work on a shared machine disturbs much less. Each is the best of its rounds.
struct Table2Row {
    int frames = 0;
    double ours_s = 0, ours_cpu_s = 0;
    double fbf_s = 0, fbf_cpu_s = 0;              // rendered in full once, or the lower bound
    double fbf_lower_s = 0, fbf_lower_cpu_s = 0;  // F x the fastest one-frame convergence seen
    bool fbf_full = false;
    double ours_rays = 0;  // camera + photon rays of one render
    // Stage times of ours' fastest round (wall seconds; camera and photon passes overlap).
    double camera_s = 0, photons_s = 0, gather_s = 0, assembly_s = 0;
};

struct CeilingNumbers {
    RayRate bare, photon_pass, render;
};

struct ScalingRow {
    int threads = 0;
    double render_s = 0, render_cpu_s = 0;  // the best render, and its CPU time
    RayRate bare, photon;
};

struct Report {
    bool quick = false;
    std::string scene_name, scene_path, command;
    int width = 0, height = 0, frames = 0;
    int64_t photons = 0;
    double alpha = 0;
    int table_passes = 0, rounds = 0, fbf_full_max = 0, fbf_ladder_max = 0;
    sl::Timeline timeline;  // the ladder's time axis: frame edges in the tables and sheets
    Machine machine;
    Reference ref;
    std::vector<LadderPoint> ladder;
    std::vector<Table2Row> table;
    CeilingNumbers ceiling;
    std::vector<ScalingRow> scaling;
    std::vector<std::pair<int, Image>> steady_by_passes;  // single convergence, ladder order
    std::vector<double> steady_wall_s;                    // their wall times
    size_t non_finite = 0, images_checked = 0;
    double total_seconds = 0;
};

// Least-squares slope of log y against log x (points with y <= 0 skipped; NaN if < 2 points).
double loglog_slope(const std::vector<double>& x, const std::vector<double>& y);

// Writes report.md, the CSVs, the gnuplot scripts and (with plots, if gnuplot runs) their
// PNGs, and the contact sheets into `dir`. Throws std::runtime_error on I/O failure.
void write_everything(const Report& r, const std::filesystem::path& dir, bool plots);

}  // namespace report
