#pragma once
// One piece of a camera path that crosses the medium. The camera pass estimates its
// in-scattering as soon as the piece is found (single scattering by next-event estimation, then
// the beam estimate of the volume photons), so a path may have any number of them and none is
// stored.
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
    // The pixel's first segment in the pass: its light samples are stratified over the passes
    // (halton_pass_point in core/pass_sequences.h) for this pixel (its index in the image) and pass; -1:
    // drawn from the path's random stream.
    int64_t stratified_pixel = -1;
    uint32_t pass = 0;
};

}  // namespace sl
