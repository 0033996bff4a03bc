#pragma once
// The camera pass of stochastic progressive photon mapping: one jittered camera path per
// pixel per pass, followed through mirrors and glass to its first diffuse surface (the visible
// point). Direct light and seen emitters are evaluated there, at once, with their own arrival
// times; photons are gathered at the visible points later in the pass.
#include <atomic>
#include <cstdint>
#include <vector>

#include "core/oct_normal.h"
#include "stages/render/camera_segments.h"
#include "stages/render/render_context.h"
#include "stages/render/section_buffer.h"

namespace sl {

// Structure of arrays, one entry per pixel (valid[p] == 0 where the path found no diffuse point).
// 31 bytes a pixel (39 with camera_tof): they live through every section.
struct VisiblePoints {
    void resize(size_t pixels, bool camera_time);
    std::vector<float> px, py, pz;     // position
    std::vector<OctNormal> normal;     // unit normal facing the camera path
    std::vector<float> wr, wg, wb;     // camera throughput x BRDF (albedo / pi)
    std::vector<double> camera_ns;     // time back to the camera (camera_tof only; else empty)
    std::vector<uint16_t> depth_left;  // photon vertices this point may still accept
    std::vector<uint8_t> valid;
};

struct CameraPassCounters {
    std::atomic<uint64_t> rays{0};
};

// Fills `vps` for pass `pass` and adds direct light, seen emitters and ambient to `buffer`.
// With a medium (ctx.medium), everything seen is attenuated by the transmittance of the camera
// path and of the shadow ray, and the path's pieces inside the medium go to `segments` (which
// must then be given) for the beam estimate.
void camera_pass(const RenderContext& ctx, int pass, VisiblePoints& vps, SectionBuffer& buffer,
                 CameraPassCounters& counters, CameraSegments* segments = nullptr);

}  // namespace sl
