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
// silhouette) cap the radius, and the region a cut keeps is checked along its border, ray by
// ray, before it is used.
//
// Where no line accounts for them (a corner, a column's narrow face, a curved silhouette), or
// the cut leaves under 80 % of the disc, the pixel may keep a star instead: the disc in 16
// equal sectors, each kept out to where the surface ends along the rays between sectors (found
// ray by ray) and short of every edge pixel in it, and no farther than the opposite sector (a
// cut's mirror, sector by sector). Its border is checked as a cut's is. The visible points on
// the surface the pixel's centre sees gather round that centre, in the star: photons and area
// alike.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/camera.h"
#include "core/oct_normal.h"
#include "core/scene_geometry.h"
#include "foundation/constants.h"

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

// A pixel's star, where no one line accounts for the edge pixels round it (a corner, a column's
// face between two edges, a curved silhouette): the disc round `centre` (what the pixel's centre
// sees) on the plane of `normal`, kept in each of kSectors equal sectors (angles in
// make_basis(normal)'s frame) out to reach[k] * scale at most, where the surface may end. Every
// visible point of the pixel on that surface gathers round the centre in that region, photons
// and area alike; others gather in the shrunk disc (the radius times `shrunk`).
struct EdgeStar {
    static constexpr int kSectors = 16;
    Vec3 centre;
    OctNormal normal;
    float scale = 0;  // reach[k] = 255 is scale * 255 (r0 or more)
    float shrunk = 1;
    uint8_t reach[kSectors] = {};

    static int sector_of(float x, float y) {
        const float a = std::atan2(y, x);  // [-pi, pi]
        const int k = static_cast<int>((a + kPi) * (kSectors / (2 * kPi)));
        return std::clamp(k, 0, kSectors - 1);
    }
    float reach_of(int k) const { return scale * reach[k]; }
    // Whether tangent-plane offset (x, y) from the centre lies in the region, for radius R.
    bool keeps(float x, float y, float R) const {
        const float d2 = x * x + y * y, rk = std::min(R, reach_of(sector_of(x, y)));
        return d2 < rk * rk;
    }
    // The region's area at radius R.
    double area(double R) const {
        double a = 0;
        for (int k = 0; k < kSectors; ++k) {
            const double rk = std::min(R, static_cast<double>(reach_of(k)));
            a += rk * rk;
        }
        return a * kPiDouble / kSectors;
    }
};

struct GatherRadii {
    // Two normals belong to one surface when their cosine is at least this (~45 degrees): the
    // gather's test, which the edge map and the planes below must share with it.
    static constexpr float kSameSurface = 0.7f;
    // Per pixel (row-major, width x height): the initial radius, min(r0, the distance to the
    // nearest edge pixel no cut accounts for), never below r0 / 64; r0 for a star's pixel.
    std::vector<float> radius;
    // Per pixel: 1 + the index of its cut in `cuts`, 0 for none. Empty when no pixel has one.
    std::vector<uint32_t> cut_of;
    std::vector<EdgeCut> cuts;
    // The same for stars (a pixel has a cut, a star or neither).
    std::vector<uint32_t> star_of;
    std::vector<EdgeStar> stars;
    // Per pixel, when any pixel has a cut or a star: the plane its centre sees (offset NaN: none).
    // A point of a cut's or a star's pixel off that pixel's surface (its other side of a
    // silhouette) gathers as the neighbour whose centre sees its plane does: the surface behind
    // a column goes on behind it, so that neighbour's disc, not one shrunk to the column's edge,
    // is the one that fits (a shrunk disc there held a photon or none: a firefly or a hole).
    struct SeenPlane {
        OctNormal normal;
        float offset = std::numeric_limits<float>::quiet_NaN();
        // Whether point x with normal n lies on this plane: normals within ~45 degrees (the
        // gather's same-surface test), x within `slack` of the plane. False when none was seen.
        bool holds(Vec3 x, Vec3 n, float slack) const {
            if (!(std::abs(offset) <= std::numeric_limits<float>::max())) return false;
            const Vec3 pn = decode_normal(normal);
            return dot(pn, n) >= kSameSurface && std::abs(dot(pn, x) - offset) <= slack;
        }
    };
    std::vector<SeenPlane> plane;
    // The neighbour (8 around `pixel`, the nearer four first) whose centre sees the plane that
    // point x with normal n lies on (normals within ~45 degrees, x within `slack` of the plane),
    // or -1. width: the image's.
    int64_t neighbour_on(size_t pixel, int width, Vec3 x, Vec3 n, float slack) const {
        if (plane.empty()) return -1;
        const int64_t w = width, h = static_cast<int64_t>(plane.size()) / w;
        const int64_t px = static_cast<int64_t>(pixel) % w, py = static_cast<int64_t>(pixel) / w;
        static constexpr int kSteps[8][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, 1}, {1, -1}, {-1, -1}};
        for (const auto& st : kSteps) {
            const int64_t qx = px + st[0], qy = py + st[1];
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            if (plane[static_cast<size_t>(qy * w + qx)].holds(x, n, slack)) return qy * w + qx;
        }
        return -1;
    }
    const EdgeCut* cut(size_t pixel) const {
        if (cut_of.empty() || cut_of[pixel] == 0) return nullptr;
        return &cuts[cut_of[pixel] - 1];
    }
    const EdgeStar* star(size_t pixel) const {
        if (star_of.empty() || star_of[pixel] == 0) return nullptr;
        return &stars[star_of[pixel] - 1];
    }
    size_t bytes() const {
        return radius.size() * sizeof(float) + (cut_of.size() + star_of.size()) * sizeof(uint32_t) +
               plane.size() * sizeof(SeenPlane) +
               cuts.size() * sizeof(EdgeCut) + stars.size() * sizeof(EdgeStar);
    }
};

// Depends on the geometry and camera only (not the seed).
GatherRadii edge_aware_radii(const SceneGeometry& geometry, const PinholeCamera& camera, int width, int height,
                             float r0);

// The area of a disc of radius R left between two parallel lines at distances `near` and `far`
// from its centre, on opposite sides of it (either may be >= R: no cut there).
double disc_between_lines(double R, double near, double far);

}  // namespace sl
