#pragma once
// The pilot that aims the lights' photons (core/emission_aim.h). A sun lights the whole scene
// from a rectangle that covers it, and in a building most of its photons land on the roof and
// the outer walls, where no camera path ever gathers them (the cathedral: about 1 in 26 enters);
// a lamp outside a window sends most of its photons onto the wall round it.
//
// Once per scene, with a seed of its own (every seed, rank, section and resume aims alike):
//  1. The cells of space the camera sees: rays through a grid of pixel centres (through mirrors
//     and glass), the surface each meets, marked with the sides it shows the camera, and the
//     stretch of the medium before it. A grid of cells about 1/64 of the scene across, each
//     grown by one cell on every side.
//  2. For each light that can be aimed (LightSet::aimable) and each of kAimCells x kAimCells
//     cells of its aimed pair of uniforms, kAimPathsPerCell photon paths traced as a pass traces
//     them: the flux of the records and volume photons they leave in seen cells (a surface
//     record on the side the camera sees), relative to the flux they start with.
//  3. The table draws the cells in proportion to that, with kAimFloor of the draws spread evenly
//     over all of them: no light is ever left out, and a photon from a cell the pilot found
//     useless carries at most 1 / kAimFloor of its unaimed flux. A light is aimed only where
//     that at least doubles the share of its photons that land where the camera sees
//     (kAimMinGain): a lamp inside the room it lights, or a room's ceiling light, keeps
//     its photons as they were. With many lights only the kAimMostLights most powerful
//     are tried, so that the pilot's cost stays bounded (a glTF scene may bring dozens).
#include <cstddef>
#include <vector>

namespace sl {

struct RenderContext;

// Aims the lights of ctx.lights (those it pays for; see above).
void aim_lights(RenderContext& ctx);

// Step 2's figures for light i, kAimCells x kAimCells row-major, for tests.
std::vector<double> light_usefulness(const RenderContext& ctx, size_t light);

// How much an aim by these figures raises the share of photons that land where the camera sees.
double aim_gain(const std::vector<double>& usefulness, double floor);

inline constexpr int kAimCells = 32;
inline constexpr int kAimPathsPerCell = 32;
inline constexpr double kAimFloor = 0.2;
inline constexpr double kAimMinGain = 2.0;
inline constexpr size_t kAimMostLights = 4;

}  // namespace sl
