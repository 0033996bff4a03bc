#pragma once
// Pinhole camera: pixel (x, y) covers [x, x+1) x [y, y+1) of the image plane, row 0 at the top,
// right = forward x up.
#include <algorithm>
#include <cmath>
#include <utility>

#include "foundation/constants.h"
#include "config/scene_desc.h"

namespace sl {

class PinholeCamera {
public:
    explicit PinholeCamera(const CameraDesc& c) : position_(c.position), width_(c.width), height_(c.height) {
        forward_ = normalize(c.look_at - c.position);
        right_ = normalize(cross(forward_, c.up));
        up_ = cross(right_, forward_);
        half_h_ = std::tan(c.vfov_deg * kPi / 360.0f);
        half_w_ = half_h_ * static_cast<float>(c.width) / static_cast<float>(c.height);
    }
    Vec3 position() const { return position_; }
    Vec3 forward() const { return forward_; }
    // Unit direction through image-plane point (px, py) in pixel units.
    Vec3 direction(float px, float py) const {
        float sx = (2 * px / width_ - 1) * half_w_;
        float sy = (1 - 2 * py / height_) * half_h_;
        return normalize(forward_ + right_ * sx + up_ * sy);
    }
    // Where p appears on the image plane, in pixel units (direction()'s inverse); false when p
    // is not in front of the camera.
    bool project(Vec3 p, float& px, float& py) const {
        const Vec3 v = p - position_;
        const float z = dot(v, forward_);
        if (!(z > 0)) return false;
        px = (dot(v, right_) / (z * half_w_) + 1) * 0.5f * static_cast<float>(width_);
        py = (1 - dot(v, up_) / (z * half_h_)) * 0.5f * static_cast<float>(height_);
        return true;
    }
    // The pixels whose rays from the camera may pass through the ball (c, rho): columns [x0, x1]
    // and rows [y0, y1], inclusive and clamped to the image; false when no ray can. Each bound is
    // the plane through the camera that holds the image's columns (rows) and touches the ball, so
    // a ray through the ball lies between the two; a ball that reaches the camera's own plane
    // spans the whole image on that axis.
    bool pixels_near(Vec3 c, float rho, int& x0, int& x1, int& y0, int& y1) const {
        const Vec3 v = c - position_;
        const double cz = dot(v, forward_), r = rho;
        if (!(cz + r > 0)) return false;  // behind the camera (or NaN)
        auto span = [&](double a, double half, int n, bool flip, int& lo, int& hi) {
            lo = 0;
            hi = n - 1;
            const double k = cz * cz - r * r;
            if (!(cz > r) || !(k > 0)) return true;
            // Planes {x = s z} that meet the ball: (a - s cz)^2 <= r^2 (1 + s^2).
            const double root = r * std::sqrt(a * a + k);
            double s0 = (a * cz - root) / k, s1 = (a * cz + root) / k;
            if (flip) std::swap(s0, s1);
            const double p0 = (flip ? 1 - s0 / half : s0 / half + 1) * 0.5 * n;
            const double p1 = (flip ? 1 - s1 / half : s1 / half + 1) * 0.5 * n;
            if (!(p1 >= 0) || !(p0 < n)) return false;
            lo = static_cast<int>(std::max(0.0, std::floor(p0)));
            hi = static_cast<int>(std::min<double>(n - 1, std::floor(p1)));
            return lo <= hi;
        };
        return span(dot(v, right_), half_w_, width_, false, x0, x1) && span(dot(v, up_), half_h_, height_, true, y0, y1);
    }
    // Width of one pixel on a plane facing the camera at distance d.
    float pixel_footprint(float d) const { return 2 * half_h_ * d / height_; }

private:
    Vec3 position_, forward_, right_, up_;
    float half_w_ = 1, half_h_ = 1;
    int width_, height_;
};

}  // namespace sl
