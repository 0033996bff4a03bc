#pragma once
// In-process renders for the report, timed from the first pass to the last assembled frame
// (the scene's BVH is built once beforehand and not counted; nothing is written to disk).
//
//   single convergence: one section over all F frames (the renderer's `--strategy single`);
//   frame by frame:     F sections of one frame each, every one a full convergence with full
//                       photon paths (the renderer's `--strategy frame-by-frame`, the paper's
//                       baseline).
#include <cstdint>
#include <memory>
#include <vector>

#include "config/run_options.h"
#include "config/scene_desc.h"
#include "stages/render/render_context.h"

namespace report {

using Image = std::vector<float>;  // w*h*3 linear radiance, row 0 at the top

struct RunResult {
    std::vector<Image> frames;  // empty when frames were not kept
    Image steady;
    double wall_s = 0;      // passes + frame assembly
    double cpu_s = 0;       // CPU time of the process (user + system) over the same span
    double camera_s = 0, photons_s = 0, gather_s = 0, assembly_s = 0;
    std::vector<double> section_s;      // wall time of each section (frame by frame: per frame)
    std::vector<double> section_cpu_s;  // CPU time of each section
    uint64_t camera_rays = 0, photon_rays = 0, photons = 0;
    int passes = 0;
    int64_t photons_per_pass = 0;
};

using sl::Strategy;
using sl::strategy_name;

// Renders every frame of ctx's timeline (and the steady image) with the given strategy, through
// the renderer's own in-process render (pipeline/render_frames.h).
// With keep_frames false the frames are still assembled (and timed) but not stored.
RunResult render(const sl::RenderContext& ctx, Strategy strategy, int passes, int64_t photons_per_pass,
                 bool keep_frames = true);

// Rays per second of wall time and per second of CPU time (best of the rounds for each).
struct RayRate {
    double per_wall_s = 0, per_cpu_s = 0;
};

// Bare Embree: random rays (origins uniform in the scene's bounds, directions uniform on the
// sphere) through the renderer's own BVH with closest-hit queries.
RayRate bare_embree_rays_per_s(const sl::RenderContext& ctx, size_t rays, int rounds);

// The photon pass alone (tracing plus the photon grid), as the renderer runs it; `rounds` runs
// of `passes` passes.
RayRate photon_pass_rays_per_s(const sl::RenderContext& ctx, int passes, int64_t photons_per_pass, int rounds);

// CPU seconds (user + system) used by this process so far.
double cpu_seconds();

// RMSE over all pixels and channels.
double rmse(const Image& a, const Image& b);
double mean(const Image& a);
size_t count_non_finite(const Image& a);

}  // namespace report
