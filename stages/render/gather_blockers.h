#pragma once
// What stands between a visible point and the photons in its gather disc. A zero-thickness
// wall on a floor has floor photons on both sides, all with the same normal: no normal test
// tells the sunlit side's photons from the shaded side's, and a point at the wall's foot
// gathered light through the sheet. So before it gathers, a visible point casts one short
// ray per quarter (sector) of its disc, along its tangent plane (tilted up a little so that a concave
// surface does not block itself); a sector whose ray meets a surface keeps only the photons
// on the point's side of that surface's plane, and the disc's area is cut to match (the
// part of the sector beyond the plane holds no photon the point can see, so dividing by the
// whole disc would darken every floor's edge where it meets a wall). A sector keeps the photons
// on the point's side of its own and its neighbours' blockers, and its area is what is left
// of it on that side of all three: clipping more than the blocker hides is unbiased (what is
// cut from the area is cut from the photons), clipping less lets light through. What is left of
// a disc cut at a wall has its centroid away from the wall: where the light changes across it
// (the shaded foot of a wall), the estimate is that of a point farther out. So each blocker is
// mirrored through the point too, at no less than a quarter of the radius (a point on the
// wall's line would keep nothing: the noise would grow without bound), and the part beyond
// the mirror is left out of both the photons and the area.
#include <cstdint>

#include "core/scene_geometry.h"
#include "foundation/vec3.h"

namespace sl {

class GatherBlockers {
public:
    static constexpr int kSectors = 4;
    // Each blocker's line mirrored through the point, at least kMirrorMin R away: the disc is
    // cut as much on the far side of the point as the blocker cuts it (tangent-plane offsets
    // (x, y) with x mx + y my > d are left out), so what is kept is centred on the point.
    static constexpr float kMirrorMin = 0.25f;
    // An edge's line (edge_radius.h): offsets x with dot(across, x) > offset lie past the edge.
    struct EdgeLine {
        Vec3 across;
        float offset;
    };
    // Rays from p (normal n, unit, facing the camera path) reaching sqrt(r2) along the disc;
    // with `edge`, the disc is cut at that line too (and at its mirror, as at a wall).
    GatherBlockers(const SceneGeometry& geometry, Vec3 p, Vec3 n, float r2, const EdgeLine* edge = nullptr);

    bool any() const { return mask_ != 0; }
    // Whether the edge line cuts this point's disc (false: the point lies on or past it).
    bool edge_cut() const { return edge_; }
    // The disc's area on the point's side of every blocker (pi r^2 when none).
    double area() const { return area_; }
    // Whether a photon at q lies on the point's side of the blockers of its sector and of the
    // two sectors beside it (a wall nearly along one sector's middle ray is missed by that ray,
    // not by its neighbours'), and inside every blocker's mirror line.
    bool visible(Vec3 q) const {
        if (!mask_ && !edge_) return true;
        const Vec3 v = q - p_;
        const float x = dot(v, t_), y = dot(v, b_);
        if (edge_ && x * edge_x_ + y * edge_y_ > edge_rho_) return false;
        for (int i = 0; i < mirrors_; ++i)
            if (x * mirror_x_[i] + y * mirror_y_[i] > mirror_d_[i]) return false;
        if (!mask_) return true;
        const int s = sector_of(x, y);
        const uint32_t near = near_mask_[s] & mask_;
        if (!near) return true;
        for (int j = s - 1; j <= s + 1; ++j) {
            const int k = j & (kSectors - 1);
            if ((near & (1u << k)) && dot(m_[k], q) < c_[k]) return false;
        }
        return true;
    }

    // The sector of tangent-plane offset (x, y): k covers angles [k, k+1) * 90 degrees.
    static int sector_of(float x, float y) {
        if (y >= 0) return x >= 0 ? 0 : 1;
        return x < 0 ? 2 : 3;
    }

private:
    Vec3 p_, t_, b_;
    Vec3 m_[kSectors];    // blocker normal, facing the point
    float c_[kSectors];   // its plane: dot(m, x) = c, minus a small margin toward the far side
    uint32_t mask_ = 0;   // sectors with a blocker
    static constexpr uint32_t near_mask_[kSectors] = {0xb, 0x7, 0xe, 0xd};  // a sector and its two neighbours
    // The mirror lines (kMirrorMin above): one per distinct blocker line, and the edge's.
    float mirror_x_[kSectors + 1], mirror_y_[kSectors + 1], mirror_d_[kSectors + 1];
    // The edge's line: tangent-plane offsets with x edge_x + y edge_y > edge_rho lie past it.
    bool edge_ = false;
    float edge_rho_ = 0, edge_x_ = 0, edge_y_ = 0;
    int mirrors_ = 0;
    double area_ = 0;
};

}  // namespace sl
