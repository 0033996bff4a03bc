#pragma once
// The pieces of this pass's camera paths that cross the medium, kept per pixel for the beam
// radiance estimate later in the pass. A fixed capacity per pixel (the primary segment and
// one after a specular bounce) keeps the camera pass free of allocation and each pixel's
// segments its own; further segments still attenuate, they only gather no in-scattering.
#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace sl {

struct CameraSegment {
    Vec3 origin;         // where the path enters the medium (or the camera inside it)
    Vec3 dir;            // unit
    float length = 0;    // to the visible point, the emitter or the medium's exit
    Vec3 beta;           // camera throughput at origin (transmittance before it included)
    uint32_t depth_left = 0;  // photon vertices this segment may still accept
    double camera_ns = 0;     // camera leg up to origin (ns), for camera_tof
};

struct CameraSegments {
    static constexpr int kPerPixel = 2;
    void resize(size_t pixels) {
        segments.resize(pixels * kPerPixel);
        count.assign(pixels, 0);
    }
    size_t pixels() const { return count.size(); }
    const CameraSegment* of(size_t pixel) const { return &segments[pixel * kPerPixel]; }
    uint64_t bytes() const { return segments.capacity() * sizeof(CameraSegment) + count.capacity(); }

    std::vector<CameraSegment> segments;  // [pixel][kPerPixel]
    std::vector<uint8_t> count;
};

}  // namespace sl
