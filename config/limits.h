#pragma once
// Accepted ranges shared by the scene file and the command line, so both report the same bounds.
#include <cstdint>

namespace sl::limits {

inline constexpr int kMaxImageSide = 16384;  // camera width and height
inline constexpr int kMaxFrames = 100000;
inline constexpr int kMaxPasses = 10'000'000;
inline constexpr int64_t kMaxPhotonsPerPass = 1'000'000'000;
inline constexpr int kMaxDepth = 1000;
inline constexpr int kMaxPulseFrames = 1'000'000;  // pulse width / frame width
inline constexpr int kMaxSections = kMaxFrames;    // at most one section per frame
inline constexpr int kMaxThreads = 4096;
inline constexpr double kMaxFps = 1000;
// Below one frame a second the containers' time bases break down (WebM's millisecond clock
// gives a wrong frame rate under 0.5 fps, 1e-4 fps makes an MP4 that does not play).
inline constexpr double kMinFps = 1;
// Every length, in meters after units: keeps squared lengths and cross products finite in float.
inline constexpr double kMaxLength = 1e9;
// Light power (W) and radiance: far beyond any real light, far below float overflow once
// multiplied by areas, albedos and photon weights.
inline constexpr double kMaxEmission = 1e30;
// A spot narrower than this is a laser: its 1 - cos(cone) would vanish in float.
inline constexpr double kMinSpotConeDeg = 0.1;
// A sun's angular diameter: a wider "sun" is an area light, not a directional one.
inline constexpr double kMaxSunAngleDeg = 45;
// A texture file, as stored (compressed): larger is not an image anyone paints.
inline constexpr uint64_t kMaxTextureFileBytes = uint64_t(1) << 30;
// What one model file may expand to once its node graph is walked (every path from a root
// places its meshes again): 2^27 triangles would need some 17 GiB of BVH alone, and 2^24 node
// visits bound a graph of empty nodes whose paths double at each level.
inline constexpr uint64_t kMaxImportedTriangles = uint64_t(1) << 27;
inline constexpr uint64_t kMaxImportedVertices = uint64_t(1) << 27;
inline constexpr uint64_t kMaxNodeVisits = uint64_t(1) << 24;

}  // namespace sl::limits
