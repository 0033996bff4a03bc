#pragma once
// Gather radii that stop short of a surface's edges. A gather disc that reaches past the edge of
// the face it lies on (a box's top edge, an object's silhouette) finds no photons beyond it but
// is still divided by its whole area, so a band of pixels along every such edge comes out dark
// (a glossy plastic cube's shadowed front face: 0.61-0.89 of Cycles along its edges at three
// pixel footprints). Walls rising from the surface are the gather blockers' (gather_blockers.h);
// this covers the surface ending. One ray through every pixel's centre finds what each pixel
// sees first; a neighbouring pixel that sees no surface, or one that drops behind this pixel's
// tangent plane or turns away from it (more than the gather's 45 degrees), marks an edge, and
// the pixel's initial radius is capped at its distance from the nearest such edge (measured on
// the tangent plane, half-way to the neighbour's ray). Pixels far from edges keep the automatic
// radius; the progressive shrink then goes on from each pixel's own.
#include <vector>

#include "core/camera.h"
#include "core/scene_geometry.h"

namespace sl {

// Per pixel (row-major, width x height): min(r0, the distance to the nearest edge seen within
// a few radii), never below r0 / 64. Depends on the geometry and camera only (not the seed).
std::vector<float> edge_aware_radii(const SceneGeometry& geometry, const PinholeCamera& camera, int width,
                                    int height, float r0);

}  // namespace sl
