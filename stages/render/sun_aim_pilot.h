#pragma once
// The pilot that aims a sun's photons (core/sun_aim.h). A sun lights the whole scene from a
// rectangle that covers it, and in a building most of its photons land on the roof and the
// outer walls, where no camera path ever gathers them (the cathedral: about 1 in 20 enters).
//
// Once per scene, with a seed of its own (every seed, rank, section and resume aims alike):
//  1. The cells of space the camera sees: rays through a grid of pixel centres (through mirrors
//     and glass), the surface each meets, marked with the sides it shows the camera, and the
//     stretch of the medium before it. A grid of cells about 1/64 of the scene across, each
//     grown by one cell on every side.
//  2. For each of kCells x kCells cells of the sun's rectangle, kPathsPerCell photon paths traced
//     as a pass traces them: the flux of the records and volume photons they leave in seen
//     cells (a surface record on the side the camera sees), relative to the flux they start with.
//  3. The table draws the cells in proportion to that, with kFloor of the draws spread evenly
//     over all of them: no light is ever left out, and a photon from a cell the pilot found
//     useless carries at most 1 / kFloor of its unaimed flux.
#include <cstddef>
#include <vector>

namespace sl {

struct RenderContext;

// Aims every sun of ctx.lights (a no-op without one, or when no pilot photon lands where the
// camera sees: the rectangle is then drawn uniformly).
void aim_suns(RenderContext& ctx);

// Step 2's figures for light i (a sun), kCells x kCells row-major, for tests.
std::vector<double> sun_usefulness(const RenderContext& ctx, size_t light);

inline constexpr int kSunAimCells = 32;
inline constexpr int kSunAimPathsPerCell = 32;
inline constexpr double kSunAimFloor = 0.2;

}  // namespace sl
