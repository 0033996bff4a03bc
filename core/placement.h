#pragma once
// How a scene places a shape or an imported file: scale, then rotate about X, then Y, then Z
// (degrees), then translate. One definition for built-in meshes and imports alike.
#include <cmath>

#include "foundation/constants.h"
#include "foundation/vec3.h"

namespace sl {

inline Vec3 rotate_xyz(Vec3 p, Vec3 deg) {
    const float k = kPi / 180.0f;
    float cx = std::cos(deg.x * k), sx = std::sin(deg.x * k);
    p = {p.x, cx * p.y - sx * p.z, sx * p.y + cx * p.z};
    float cy = std::cos(deg.y * k), sy = std::sin(deg.y * k);
    p = {cy * p.x + sy * p.z, p.y, -sy * p.x + cy * p.z};
    float cz = std::cos(deg.z * k), sz = std::sin(deg.z * k);
    return {cz * p.x - sz * p.y, sz * p.x + cz * p.y, p.z};
}

}  // namespace sl
