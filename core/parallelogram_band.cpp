#include "core/parallelogram_band.h"

#include <algorithm>
#include <cmath>

#include "foundation/constants.h"

namespace sl {
namespace {

constexpr double kTwoPi = 2 * kPiDouble;

// The squared distance from (px, py) to the segment (ax, ay)-(bx, by).
double segment_distance2(double px, double py, double ax, double ay, double bx, double by) {
    const double ex = bx - ax, ey = by - ay;
    const double len2 = ex * ex + ey * ey;
    double s = len2 > 0 ? ((px - ax) * ex + (py - ay) * ey) / len2 : 0.0;
    s = std::clamp(s, 0.0, 1.0);
    const double dx = px - ax - s * ex, dy = py - ay - s * ey;
    return dx * dx + dy * dy;
}

}  // namespace

ParallelogramFromPoint::ParallelogramFromPoint(Vec3 x, Vec3 corner, Vec3 edge1, Vec3 edge2) : corner_(corner) {
    const double e1x = edge1.x, e1y = edge1.y, e1z = edge1.z, e2x = edge2.x, e2y = edge2.y, e2z = edge2.z;
    double nx = e1y * e2z - e1z * e2y, ny = e1z * e2x - e1x * e2z, nz = e1x * e2y - e1y * e2x;
    const double nlen = std::sqrt(nx * nx + ny * ny + nz * nz);
    const double l1 = std::sqrt(e1x * e1x + e1y * e1y + e1z * e1z);
    if (!(nlen > 0) || !(l1 > 0) || !std::isfinite(nlen)) return;
    nx /= nlen, ny /= nlen, nz /= nlen;
    const double ax = e1x / l1, ay = e1y / l1, az = e1z / l1;  // t1 along edge1
    const double bx = ny * az - nz * ay, by = nz * ax - nx * az, bz = nx * ay - ny * ax;  // t2 = n x t1
    t1_ = Vec3(static_cast<float>(ax), static_cast<float>(ay), static_cast<float>(az));
    t2_ = Vec3(static_cast<float>(bx), static_cast<float>(by), static_cast<float>(bz));
    const double rx = double(x.x) - corner.x, ry = double(x.y) - corner.y, rz = double(x.z) - corner.z;
    const double z = rx * nx + ry * ny + rz * nz;
    z2_ = z * z;
    px_ = rx * ax + ry * ay + rz * az;
    py_ = rx * bx + ry * by + rz * bz;
    // Corners 0, edge1, edge1 + edge2, edge2: counter-clockwise about n = edge1 x edge2.
    const double e2a = e2x * ax + e2y * ay + e2z * az, e2b = e2x * bx + e2y * by + e2z * bz;
    const double cx[4] = {0, l1, l1 + e2a, e2a}, cy[4] = {0, 0, e2b, e2b};
    bool inside = true;
    double near2 = INFINITY, far2 = 0;
    for (int i = 0; i < 4; ++i) {
        vx_[i] = cx[i], vy_[i] = cy[i];
        const int j = (i + 1) % 4;
        const double ex = cx[j] - cx[i], ey = cy[j] - cy[i];
        const double el = std::sqrt(ex * ex + ey * ey);
        mx_[i] = -ey / el, my_[i] = ex / el;  // left of the edge: inside
        inside_[i] = (px_ - cx[i]) * mx_[i] + (py_ - cy[i]) * my_[i];
        theta_[i] = std::atan2(my_[i], mx_[i]);
        inside = inside && inside_[i] >= 0;
        near2 = std::min(near2, segment_distance2(px_, py_, cx[i], cy[i], cx[j], cy[j]));
        const double dx = px_ - cx[i], dy = py_ - cy[i];
        far2 = std::max(far2, dx * dx + dy * dy);
    }
    rho_min2_ = inside ? 0.0 : near2;
    rho_max2_ = far2;
    d_min_ = std::sqrt(z2_ + rho_min2_);
    d_max_ = std::sqrt(z2_ + rho_max2_);
    valid_ = std::isfinite(d_max_);
}

int ParallelogramFromPoint::arcs(double rho, double lo[kMaxArcs], double hi[kMaxArcs]) const {
    int n = 1;
    lo[0] = 0, hi[0] = kTwoPi;
    for (int e = 0; e < 4 && n > 0; ++e) {
        // Inside edge e's line: inside_ + rho cos(phi - theta) >= 0.
        if (!(rho > 0)) {
            if (inside_[e] < 0) return 0;
            continue;
        }
        const double kappa = -inside_[e] / rho;
        if (kappa <= -1) continue;  // the whole circle is on the inner side
        if (kappa >= 1) return 0;
        const double w = std::acos(kappa);
        double a = theta_[e] - w;
        a -= kTwoPi * std::floor(a / kTwoPi);
        const double b = a + 2 * w;
        // The arc as one or two intervals of [0, 2 pi), intersected with the ones kept so far.
        const double arc_lo[2] = {a, 0.0}, arc_hi[2] = {std::min(b, kTwoPi), b - kTwoPi};
        const int parts = b > kTwoPi ? 2 : 1;
        double nlo[kMaxArcs], nhi[kMaxArcs];
        int m = 0;
        for (int i = 0; i < n; ++i)
            for (int k = 0; k < parts; ++k) {
                const double l = std::max(lo[i], arc_lo[k]), h = std::min(hi[i], arc_hi[k]);
                if (h > l && m < kMaxArcs) nlo[m] = l, nhi[m++] = h;
            }
        n = m;
        for (int i = 0; i < n; ++i) lo[i] = nlo[i], hi[i] = nhi[i];
    }
    return n;
}

bool ParallelogramFromPoint::sample_band(double d0, double d1, float u1, float u2, Vec3& y, double& weight) const {
    weight = 0;
    if (!valid_) return false;
    const double a = std::max(d0 * d0 - z2_, rho_min2_), b = std::min(d1 * d1 - z2_, rho_max2_);
    if (!(b > a)) return false;
    const double rho = std::sqrt(a + static_cast<double>(u1) * (b - a));
    double lo[kMaxArcs], hi[kMaxArcs];
    const int n = arcs(rho, lo, hi);
    double total = 0;
    for (int i = 0; i < n; ++i) total += hi[i] - lo[i];
    if (!(total > 0)) return false;
    // The angle: u2 of the way along the arcs laid end to end.
    double s = static_cast<double>(u2) * total, phi = hi[n - 1];
    for (int i = 0; i < n; ++i) {
        const double len = hi[i] - lo[i];
        if (s < len) {
            phi = lo[i] + s;
            break;
        }
        s -= len;
    }
    const double qx = px_ + rho * std::cos(phi), qy = py_ + rho * std::sin(phi);
    y = corner_ + t1_ * static_cast<float>(qx) + t2_ * static_cast<float>(qy);
    weight = 0.5 * (b - a) * total;
    return true;
}

}  // namespace sl
