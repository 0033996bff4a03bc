#pragma once
// Pinhole camera: pixel (x, y) covers [x, x+1) x [y, y+1) of the image plane, row 0 at the top,
// right = forward x up.
#include <cmath>

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
    // Width of one pixel on a plane facing the camera at distance d.
    float pixel_footprint(float d) const { return 2 * half_h_ * d / height_; }

private:
    Vec3 position_, forward_, right_, up_;
    float half_w_ = 1, half_h_ = 1;
    int width_, height_;
};

}  // namespace sl
