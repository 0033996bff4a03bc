#pragma once
// Everything a convergence reads and never changes: the scene, its BVH, lights, camera,
// time axis and the settings that shape the estimate.
#include <memory>
#include <mutex>
#include <optional>
#include <array>
#include <vector>

#include "foundation/constants.h"
#include "config/scene_desc.h"
#include "core/camera.h"
#include "core/light_set.h"
#include "core/material_table.h"
#include "stages/render/edge_radius.h"
#include "core/medium.h"
#include "core/scene_geometry.h"
#include "foundation/timeline.h"
#include "stages/render/rank_exchange.h"

namespace sl {

struct RenderContext {
    // Builds from a scene whose imported files were read (resolve_imports): it reads no file.
    explicit RenderContext(const SceneDesc& desc);

    SceneDesc scene;             // as parsed: for the checks and the exposure preview, not the passes
    RenderDesc render;           // what the passes' loops read: seed, depth, alpha, camera_tof, ambient
    EmissionMode emission = EmissionMode::Constant;
    SceneGeometry geometry;
    LightSet lights;
    MaterialTable materials;     // what the tracers read at a hit (built from scene.materials)
    PinholeCamera camera;
    Timeline timeline;           // timeline_of(scene): Δ, edges, buckets, the pulse's buckets
    float initial_radius = 0;    // meters
    // Per pixel (the image's, row-major): the automatic radius capped at the distance to the
    // nearest edge of the surface the pixel sees (edge_radius.h); empty when the scene sets its
    // radius (every pixel starts at initial_radius). Made at the first call (a ray a pixel:
    // `info` and the memory plan's pilot never need it), by any thread.
    // Where a pixel's disc is cut at an edge's line instead, the cut (GatherRadii::cut).
    const GatherRadii& gather_radii() const;
    // The medium, only when there is something to compute (present, some extinction, a box
    // of some volume): without it every stage runs its vacuum code and allocates nothing.
    std::optional<HomogeneousMedium> medium;
    float volume_radius = 0;     // initial radius of the beam estimate (meters), with a medium
    // false (always, for the program): the camera pass computes single scattering in the medium
    // by next-event estimation and volume photons of depth 1 are not stored (but lasers').
    // true: the estimator before it, every volume photon stored and the camera pass sampling
    // no light in the medium; kept only so that tests can compare the two (not a scene key).
    bool single_scatter_by_photons = false;
    // true (always, for the program): at a glossy vertex camera paths follow, direct light is
    // the light samples and the followed direction's hits on emitters, weighed by the power
    // heuristic (camera_pass.cpp). false: light samples alone; kept for tests that compare.
    bool glossy_mis = true;
    // A camera path splits into this many at its first followed glossy vertex (smooth metals),
    // each branch with 1/n of its weight and its draw stratified (stratified_draw): the light
    // through a sharp lobe varies from direction to direction far more than elsewhere, and
    // camera paths cost little next to the photons. 1: no split (tests that compare).
    int glossy_split = 8;
    // The same where the vertex is a rough dielectric's (glass): a branch that enters the solid
    // meets at least one more rough interface, whose lobe multiplies the variance again, so
    // more branches (the glass cube's top, spread over 32 seeds: 32 stratified 2.1 %, with the
    // second interface's draws stratified too 1.8 %, 64 of them 1.2 %, for 1.67x the glass
    // scene's time: 2.1x less variance, so less noise for the CPU spent as well).
    int glossy_split_transmissive = 64;
    // true (the program): a metallic-roughness surface with a smooth coat (smooth_coat in
    // core/glossy_path.h) gathers its diffuse base and has its coat followed in one leg.
    // false: it gathers all of it; kept for tests that compare.
    bool follow_coats = true;
    // true (the program): every photon path's first numbers come from a randomised
    // low-discrepancy sequence (photon_qmc.h). false: all from its random stream; kept for tests that compare.
    bool photon_qmc = true;
    // true: each pixel's first light samples of a pass come from a sequence stratified over the
    // passes (camera_pass.cpp, light_pass_point); false: from its random stream (tests compare).
    bool stratified_light_points = true;
    // true (the program): with pulse emission, a rectangular quad's in-scattering is taken from
    // one point of its area per camera segment, so that each frame's distance sample lands in
    // that frame (single_scatter.cpp); false: by solid angle at every sample, as with constant
    // emission (tests compare).
    bool pulse_quads_by_area = true;
    // true (the program): with pulse emission, a quad's direct light at a diffuse point is one
    // sample per bucket its light reaches the point in (direct_by_frames.h); false: one sample
    // of the whole quad, landing in one bucket, as with constant emission, whose frames sum the
    // buckets and gained nothing measurable from it for 1.2-1.3x the CPU (tests compare).
    bool pulse_direct_by_frames = true;
    // true (the program): beside an edge, a pixel's disc keeps its size and is cut at the edge's
    // line where one accounts for it (edge_radius.h); false: every point of such a pixel
    // gathers in the disc shrunk to the edge's distance, as before the cuts (tests compare).
    bool edge_cuts = true;
    // true (the program): where no line does, or its cut leaves little, a pixel's points on the
    // surface its centre sees gather in its star (edge_radius.h); false: they gather as if the
    // pixel had no star (the shrunk disc), to compare (tests). Stars need edge_cuts too.
    bool edge_stars = true;
    // true (the program): a point of a pixel beside an edge that lies off the surface its centre
    // sees (across a silhouette, on the wall behind a column) gathers as the neighbouring pixel
    // whose centre sees its surface does (edge_radius.h, GatherRadii::plane); false: in the disc
    // shrunk to the edge's distance, to compare (tests).
    bool edge_neighbours = true;
    // The beam estimate of the segments that leave the camera from the photons' side
    // (beam_splat.h); off, every segment searches the volume BVH: the same estimate, for tests.
    bool beam_splat = true;
    // true (the program): the lights' photons are aimed where the camera sees, where that pays
    // (emission_aim_pilot.h), by a pilot run in the constructor; tests that compare clear the
    // aim (LightSet::aim).
    static constexpr bool aim_photons = true;
    // Image positions (pixel units) of the point and spot lights inside the medium in front of
    // the camera: the pixels round them sample their rays towards them (camera_pass.cpp).
    std::vector<std::array<float, 2>> light_images;
    int width = 0, height = 0;
    // The other processes rendering this image with this one (MPI ranks); null: this one alone.
    RankExchange* exchange = nullptr;
    size_t pixels() const { return static_cast<size_t>(width) * height; }
    bool has_ambient() const { return !is_black(render.ambient); }

private:
    // The beam estimate's automatic radius, widened where the volume photons are sparse: a beam
    // query across the medium (half its diagonal long) should meet about kBeamPhotons of one
    // pass's volume photons, spread evenly through its box, and the footprint rule alone leaves
    // far fewer in a large, thin haze (the cathedral: about 12; a sun's photons mostly land
    // outside). The count per pass comes from a pilot of kVolumePilotPaths paths with a seed of
    // its own (every seed of a scene, every rank and section get the same radius); the radius
    // grows at most 4x and stays under 5 % of the medium's size. 80: since the segments from the
    // camera take their photons from the photons' side (beam_splat.h), a photon taken costs less
    // than half of what it did, and twice the photons of 40 pay (the cathedral: noise^2 x CPU 1.29x
    // lower, its error against a 256-pass reference lower too; docs/medium.md).
    static constexpr double kBeamPhotons = 80;
    static constexpr int64_t kVolumePilotPaths = 4 * 4096;
    static constexpr uint64_t kPilotSeed = 0x5eed;
    float widened_for_sparse_photons(float r, const HomogeneousMedium& m);

    bool automatic_radius_ = true;
    mutable std::once_flag radii_once_;
    mutable GatherRadii gather_radii_;
};

// The initial gather radius: the scene's own, or about three pixel footprints at the middle of
// the scene, capped at 5% of the scene's size.
float choose_initial_radius(const SceneDesc& desc, const SceneGeometry& geometry, const PinholeCamera& camera);
// How much wider a pulse's automatic surface radius starts than a steady light's. A pulse's frame
// holds only the photons that arrive within it, about width_frames / frames of them; a density
// estimate's best radius grows as its photon count falls, as N^(-1/6) on a surface, so the discs
// start (frames / width_frames)^(1/6) wider, at most 2x (1 for constant emission; 31 frames: 1.77x).
float pulse_radius_factor(const SceneDesc& desc);

// The initial volume radius: the scene's own, or about three pixel footprints at the middle of
// the medium (but at least a tenth of its size away), capped at 5% of the medium's size; then
// widened where the volume photons are sparse (RenderContext::widened_for_sparse_photons).
float choose_volume_radius(const SceneDesc& desc, const HomogeneousMedium& medium, const PinholeCamera& camera);

}  // namespace sl
