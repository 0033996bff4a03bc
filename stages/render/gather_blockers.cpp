#include "stages/render/gather_blockers.h"

#include <algorithm>
#include <cmath>

#include "core/sampling.h"
#include "stages/render/edge_radius.h"

namespace sl {
namespace {

constexpr float kSectorAngle = 1.5707963267948966f;  // 90 degrees
// The rays rise at 1 in 2: a concave surface (curvature radius above about 1.3 r) stays under
// them, while a wall on the surface meets them at height r/2 at most.
constexpr float kCos = 0.894427191f, kSin = 0.447213595f;
constexpr float kReach = 1.5f;  // horizontal reach in radii: a wall across a sector's edge

constexpr int kSteps = 32;  // per sector, for the area

// The midpoint directions of the area's steps: (cos, sin) of (i + 1/2) 90 degrees / kSteps.
struct StepDirections {
    float c[GatherBlockers::kSectors * kSteps], s[GatherBlockers::kSectors * kSteps];
    StepDirections() {
        for (int i = 0; i < GatherBlockers::kSectors * kSteps; ++i) {
            const double a = (i + 0.5) * (kSectorAngle / kSteps);
            c[i] = static_cast<float>(std::cos(a));
            s[i] = static_cast<float>(std::sin(a));
        }
    }
};
const StepDirections kStep;

// Area of sector `sector` of a disc of radius R left on the near side of the lines given by
// their distance rho from the centre and unit direction (ux, uy) toward them: the distance out
// to the nearest line, min(R, rho / cos), integrated as r^2 / 2 by the midpoint rule over 32
// steps of 2.8 degrees (several different lines: a corner).
double clipped_sector_area(int sector, const float* rho, const float* ux, const float* uy, int lines, float R) {
    const double h = kSectorAngle / kSteps;
    double sum = 0;
    for (int i = sector * kSteps; i < (sector + 1) * kSteps; ++i) {
        float r = R;
        for (int j = 0; j < lines; ++j) {
            const float c = kStep.c[i] * ux[j] + kStep.s[i] * uy[j];
            if (rho[j] < r * c) r = rho[j] / c;
        }
        sum += 0.5 * static_cast<double>(r) * r;
    }
    return sum * h;
}

// The same for one line, exactly: over the angles within acos(rho / R) of the line's direction
// psi the area out to the line, rho^2 tan / 2, replaces the disc's R^2 / 2 per radian.
double clipped_sector_area(int sector, float rho, float ux, float uy, float R) {
    constexpr double kTwoPi = 6.283185307179586;
    const double a0 = sector * static_cast<double>(kSectorAngle), a1 = a0 + kSectorAngle;
    const double R2 = static_cast<double>(R) * R, rh = rho;
    double area = 0.5 * R2 * (a1 - a0);
    if (rh >= R) return area;
    const double phic = std::acos(rh / R), psi = std::atan2(uy, ux);
    const double lo0 = std::remainder(a0 - psi, kTwoPi), hi0 = lo0 + (a1 - a0);
    for (double w : {-kTwoPi, 0.0, kTwoPi}) {
        const double lo = std::max(lo0, w - phic), hi = std::min(hi0, w + phic);
        if (lo < hi) area -= 0.5 * R2 * (hi - lo) - 0.5 * rh * rh * (std::tan(hi - w) - std::tan(lo - w));
    }
    return area;
}

// What the last point query on this thread found: no surface within rho of o rises above hq
// over the plane through p with normal n (in the scene geometry `scene`).
struct ClearBall {
    uint64_t scene = 0;
    Vec3 o, p, n;
    float rho = -1, hq = 0;
};
thread_local ClearBall last_clear;
constexpr float kQueryWidth = 4.0f;  // the query's radius, in the rays' reach

// Whether no surface within `reach` of o rises above `height` over the plane (p, n). Only the
// time taken depends on the thread's earlier points: the answer is the geometry's.
bool nothing_rises(const SceneGeometry& geometry, Vec3 o, float reach, Vec3 p, Vec3 n, float height) {
    ClearBall& c = last_clear;
    if (c.scene == geometry.id() && n.x == c.n.x && n.y == c.n.y && n.z == c.n.z) {
        // Heights over this point's plane are those over the cached one plus dot(n, p' - p).
        const float shift = std::abs(dot(n, c.p - p));
        if (c.hq + shift <= 0.8f * height && length(o - c.o) + reach <= 0.999f * c.rho) return true;
    }
    const float hq = 0.5f * height;  // stricter than needed, so the ball serves points a little off the plane
    const float rho = geometry.clear_radius(o, kQueryWidth * reach, p, n, hq);
    c = ClearBall{geometry.id(), o, p, n, rho, hq};
    return rho > reach;
}

}  // namespace

GatherBlockers::GatherBlockers(const SceneGeometry& geometry, Vec3 p, Vec3 n, float r2, const EdgeLine* edge)
    : p_(p) {
    make_basis(n, t_, b_);
    const float R = std::sqrt(r2);
    area_ = kPi * static_cast<double>(r2);
    // The edge's line on this point's tangent plane (the cut was made at the pixel's centre, on
    // its surface: this point lies a little off it). A point on or past the line has no side to
    // keep: the caller gathers without the cut then.
    float edge_rho = 0, edge_x = 0, edge_y = 0;
    if (edge) {
        const float gt = dot(edge->across, t_), gb = dot(edge->across, b_), gl = std::sqrt(gt * gt + gb * gb);
        const float d = edge->offset - dot(edge->across, p);
        if (gl > 0.5f && d > 0) {
            edge_ = true;
            edge_rho_ = edge_rho = d / gl;
            edge_x_ = edge_x = gt / gl;
            edge_y_ = edge_y = gb / gl;
        }
    }
    const float lift = std::max(ray_epsilon(p, R), 1e-3f * R);
    const Vec3 o = p + n * lift;
    const float tmax = kReach * R / kCos;
    // Every point of the rays lies within tmax of o and at least `lift` above the point's
    // tangent plane: when no surface there rises above half that height (open ground, the
    // point's own surface lying under the rays), all four would miss, so the answer is the rays'
    // own and the pixels do not change. A point query, wider than the rays' reach, answers that;
    // the clear ball it finds also answers for the next points on this thread that lie on the
    // same plane well inside it (neighbouring pixels of one floor): a few queries for many points.
    float rho[kSectors], ux[kSectors], uy[kSectors];  // each blocker's trace on the tangent plane
    bool cuts[kSectors] = {};
    const bool walls = !nothing_rises(geometry, o, tmax * 1.001f, p, n, 0.5f * lift);
    for (int s = 0; walls && s < kSectors; ++s) {
        const float a = (static_cast<float>(s) + 0.5f) * kSectorAngle;
        const Vec3 u = t_ * std::cos(a) + b_ * std::sin(a);
        const Vec3 d = u * kCos + n * kSin;
        SurfaceHit hit;
        if (!geometry.intersect(o, d, 0, tmax, hit)) continue;
        Vec3 m = dot(hit.normal, d) < 0 ? hit.normal : -hit.normal;
        const float c = dot(m, hit.position);
        const float h = dot(m, p) - c;  // the point's height over the blocker's plane
        if (!(h > 0)) continue;  // a surface that leans over the point: no side to keep
        m_[s] = m;
        // The boundary moves toward the point by a rounding error's width, never away: a lit
        // floor's photons a millimetre past a sheet outweigh the shaded side's own light
        // hundreds of times over (a margin of R/1000 the other way let 20% more through).
        const float margin = ray_epsilon(hit.position, 0);
        c_[s] = c + margin;
        mask_ |= 1u << s;
        // The plane's trace on the tangent plane: offsets x t + y b with x gt + y gb < -h' lie beyond.
        const float gt = dot(m, t_), gb = dot(m, b_), gl = std::sqrt(gt * gt + gb * gb);
        if (gl < 1e-6f) continue;  // parallel to the disc: cuts nothing of it
        rho[s] = std::max(0.0f, h - margin) / gl;
        ux[s] = -gt / gl;
        uy[s] = -gb / gl;
        cuts[s] = true;
    }
    // The mirrors: one per distinct line (a wall met by two rays counts once).
    auto distinct = [&](const float* r, const float* x, const float* y, int n, float rk, float xk, float yk) {
        for (int i = 0; i < n; ++i)
            if (std::abs(r[i] - rk) <= 1e-4f * R && x[i] * xk + y[i] * yk > 0.99999f) return false;
        return true;
    };
    for (int s = 0; s < kSectors; ++s) {
        if (!cuts[s]) continue;
        const float d = std::max(rho[s], kMirrorMin * R);
        if (distinct(mirror_d_, mirror_x_, mirror_y_, mirrors_, d, -ux[s], -uy[s]))
            mirror_d_[mirrors_] = d, mirror_x_[mirrors_] = -ux[s], mirror_y_[mirrors_++] = -uy[s];
    }
    if (edge_) {
        const float d = std::max(edge_rho, kMirrorMin * R);
        if (distinct(mirror_d_, mirror_x_, mirror_y_, mirrors_, d, -edge_x, -edge_y))
            mirror_d_[mirrors_] = d, mirror_x_[mirrors_] = -edge_x, mirror_y_[mirrors_++] = -edge_y;
        if (!mask_) {  // the edge alone: two parallel chords, exactly
            area_ = disc_between_lines(R, edge_rho, d);
            area_ = std::max(area_, kPi * static_cast<double>(r2) * 1e-3);
            return;
        }
    }
    for (int s = 0; mask_ && s < kSectors; ++s) {
        float r[5 + kSectors], x[5 + kSectors], y[5 + kSectors];  // edge, 3 walls, 5 mirrors
        int lines = 0;
        if (edge_) r[lines] = edge_rho, x[lines] = edge_x, y[lines++] = edge_y;
        for (int j = s - 1; j <= s + 1; ++j) {
            const int k = j & (kSectors - 1);
            if (cuts[k] && distinct(r, x, y, lines, rho[k], ux[k], uy[k]))
                r[lines] = rho[k], x[lines] = ux[k], y[lines++] = uy[k];
        }
        for (int i = 0; i < mirrors_; ++i) r[lines] = mirror_d_[i], x[lines] = mirror_x_[i], y[lines++] = mirror_y_[i];
        if (!lines) continue;
        const double sector = 0.5 * static_cast<double>(R) * R * kSectorAngle;
        double kept;
        if (lines == 1) {
            kept = clipped_sector_area(s, r[0], x[0], y[0], R);
        } else if (lines == 2 && x[0] * x[1] + y[0] * y[1] < -0.99999f) {
            // A wall and its mirror: the two cuts lie on opposite sides and never overlap.
            kept = clipped_sector_area(s, r[0], x[0], y[0], R) + clipped_sector_area(s, r[1], x[1], y[1], R) - sector;
        } else {
            kept = clipped_sector_area(s, r, x, y, lines, R);
        }
        area_ -= sector - kept;
    }
    // Only a guard: a point in a corner keeps a quarter of the disc within R/4 of it at least.
    area_ = std::max(area_, kPi * static_cast<double>(r2) * 1e-3);
}

}  // namespace sl
