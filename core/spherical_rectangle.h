#pragma once
// Uniform sampling of the solid angle a rectangle subtends from a point (Urena, Fajardo and
// King, "An Area-Preserving Parametrization for Spherical Rectangles", EGSR 2013). Used for the
// in-scattering of quad lights in the medium: sampled by area, a point near the light sees
// cos / d^2 vary without bound over the quad (the haze round a ceiling light was grain); sampled
// by solid angle, the estimate of the quad's radiance integral is L * Omega exactly, up to the
// phase function and visibility.
#include <algorithm>
#include <cmath>

#include "foundation/constants.h"
#include "foundation/vec3.h"

namespace sl {

struct SphericalRectangle {
    Vec3 o, x, y, z;  // the point and the rectangle's frame (z from the point's side)
    float z0 = 0, x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    float b0 = 0, b1 = 0, k = 0;
    float solid_angle = 0;

    // s: a corner; ex, ey: its two edges, at right angles.
    SphericalRectangle(Vec3 point, Vec3 s, Vec3 ex, Vec3 ey) : o(point) {
        const float exl = length(ex), eyl = length(ey);
        x = ex / exl;
        y = ey / eyl;
        z = cross(x, y);
        const Vec3 d = s - o;
        z0 = dot(d, z);
        if (z0 > 0) {
            z = -z;
            z0 = -z0;
        }
        x0 = dot(d, x);
        y0 = dot(d, y);
        x1 = x0 + exl;
        y1 = y0 + eyl;
        if (!(z0 < 0)) return;  // the point in the rectangle's plane: no solid angle
        const Vec3 n0 = normalize(Vec3(0, z0, -y0)), n1 = normalize(Vec3(-z0, 0, x1));
        const Vec3 n2 = normalize(Vec3(0, -z0, y1)), n3 = normalize(Vec3(z0, 0, -x0));
        auto angle = [](Vec3 a, Vec3 b) { return std::acos(std::clamp(-dot(a, b), -1.0f, 1.0f)); };
        const float g0 = angle(n0, n1), g1 = angle(n1, n2), g2 = angle(n2, n3), g3 = angle(n3, n0);
        b0 = n0.z;
        b1 = n2.z;
        k = 2 * kPi - g2 - g3;
        solid_angle = g0 + g1 - k;
    }

    // A point of the rectangle, uniform in the solid angle (pdf 1 / solid_angle).
    Vec3 sample(float u, float v) const {
        const float au = u * solid_angle + k;
        const float fu = (std::cos(au) * b0 - b1) / std::sin(au);
        float cu = (fu > 0 ? 1.0f : -1.0f) / std::sqrt(fu * fu + b0 * b0);
        cu = std::clamp(cu, -1.0f, 1.0f);
        float xu = -(cu * z0) / std::sqrt(std::max(1e-12f, 1 - cu * cu));
        xu = std::clamp(xu, x0, x1);
        const float d = std::sqrt(xu * xu + z0 * z0);
        const float h0 = y0 / std::sqrt(d * d + y0 * y0), h1 = y1 / std::sqrt(d * d + y1 * y1);
        const float hv = h0 + v * (h1 - h0), hv2 = hv * hv;
        const float yv = hv2 < 1 - 1e-6f ? (hv * d) / std::sqrt(1 - hv2) : y1;
        return o + x * xu + y * std::clamp(yv, y0, y1) + z * z0;
    }
};

}  // namespace sl
