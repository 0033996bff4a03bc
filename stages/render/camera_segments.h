#pragma once
// The pieces of one camera path that cross the medium, kept while the pixel is traced for the
// beam radiance estimate at its end. A fixed capacity (the primary segment and one after a
// specular bounce) keeps the camera pass free of allocation; further segments still attenuate,
// they only gather no in-scattering.
#include <cstdint>

#include "foundation/vec3.h"

namespace sl {

struct CameraSegment {
    Vec3 origin;         // where the path enters the medium (or the camera inside it)
    Vec3 dir;            // unit
    float length = 0;    // to the visible point, the emitter or the medium's exit
    Vec3 beta;           // camera throughput at origin (transmittance before it included)
    uint32_t depth_left = 0;  // photon vertices this segment may still accept
    double camera_ns = 0;     // camera leg up to origin (ns), for camera_tof
};

struct PixelSegments {
    static constexpr int kCapacity = 2;
    CameraSegment segment[kCapacity];
    int count = 0;
};

}  // namespace sl
