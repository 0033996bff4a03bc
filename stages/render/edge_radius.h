#pragma once
// Gather radii that stop short of a surface's edges. A gather disc that reaches past the edge of
// the face it lies on (a box's top edge, an object's silhouette) finds no photons beyond it but
// is still divided by its whole area, so a band of pixels along every such edge comes out dark
// (a glossy plastic cube's shadowed front face: 0.61-0.89 of Cycles along its edges at three
// pixel footprints). Walls rising from the surface are the gather blockers' (gather_blockers.h);
// this covers the surface ending. One ray through every pixel's centre finds what each pixel
// sees first; a neighbouring pixel that sees no surface, or one that drops behind this pixel's
// tangent plane or turns away from it (more than the gather's 45 degrees), marks an edge.
//
// Shrinking the disc to the edge's distance costs noise: a pixel beside an edge gathers in a
// disc a fraction of its neighbours' (the haze samples' time slices were a third noisier for
// it). So where one straight line accounts for the edge pixels round a pixel, the disc keeps
// its size and is cut at that line instead (an edge cut): photons beyond it are left out and so
// is the area, as the blockers do at walls, and the line is mirrored through the point as
// theirs are. The line stands where the surface ends, found by bisection between the pixels'
// rays for the edge pixels near the pixel: the surface goes on up to it, so nothing before it
// is missing from the area. Edge pixels the line does not account for (a corner, a curved
// silhouette) still cap the radius, at their distance as before, and the region a cut keeps is
// checked along its border, ray by ray, before it is used.
#include <cstdint>
#include <vector>

#include "core/camera.h"
#include "core/oct_normal.h"
#include "core/scene_geometry.h"

namespace sl {

// A pixel's edge cut, in scene space. The pixel's centre sees a point on the plane
// dot(normal, x) = plane; the cut keeps dot(across, x) <= offset (across: unit, on that plane,
// pointing over the edge). A visible point of the pixel off that surface, or past the line,
// gathers in the shrunk disc instead: its radius is the cut's radius times `shrunk` (<= 1).
struct EdgeCut {
    OctNormal across;
    float offset = 0;
    OctNormal normal;
    float plane = 0;
    float shrunk = 1;
};

struct GatherRadii {
    // Per pixel (row-major, width x height): the initial radius, min(r0, the distance to the
    // nearest edge pixel no cut accounts for), never below r0 / 64.
    std::vector<float> radius;
    // Per pixel: 1 + the index of its cut in `cuts`, 0 for none. Empty when no pixel has one.
    std::vector<uint32_t> cut_of;
    std::vector<EdgeCut> cuts;
    const EdgeCut* cut(size_t pixel) const {
        if (cut_of.empty() || cut_of[pixel] == 0) return nullptr;
        return &cuts[cut_of[pixel] - 1];
    }
    size_t bytes() const {
        return radius.size() * sizeof(float) + cut_of.size() * sizeof(uint32_t) + cuts.size() * sizeof(EdgeCut);
    }
};

// Depends on the geometry and camera only (not the seed).
GatherRadii edge_aware_radii(const SceneGeometry& geometry, const PinholeCamera& camera, int width, int height,
                             float r0);

// The area of a disc of radius R left between two parallel lines at distances `near` and `far`
// from its centre, on opposite sides of it (either may be >= R: no cut there).
double disc_between_lines(double R, double near, double far);

}  // namespace sl
