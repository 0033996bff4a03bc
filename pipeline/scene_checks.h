#pragma once
// What can be known about a scene's light before rendering it, from a few thousand rays: its
// size, the time light needs to cross it, when direct light first and last reaches what the
// camera sees, and the mistakes that would otherwise end in a black video with exit status 0
// (the time window closing before any reflected light arrives, a light outside the closed room
// the camera is in, coordinates that look like centimeters read as meters).
#include <optional>
#include <string>
#include <vector>

#include "config/scene_desc.h"
#include "foundation/vec3.h"

namespace sl {

struct RenderContext;

struct SceneFacts {
    Vec3 size;                 // extent of the geometry's bounding box, meters
    double diagonal_m = 0;
    double crossing_ns = 0;    // diagonal / c
    size_t triangles = 0;
    int spheres = 0;
    // Arrival at the camera (camera leg included with camera_tof) of light that left a light at
    // t = 0 and reached a surface the camera sees: the earliest possible (straight lines,
    // occluders ignored: nothing reflected can come sooner) and the latest along an unblocked
    // straight line. Empty when no light faces anything the camera sees.
    std::optional<double> first_arrival_ns, last_direct_arrival_ns;
    bool camera_enclosed = false;      // every direction from the camera hits a surface
    std::vector<int> lights_outside;   // lights outside that closed room
};

SceneFacts scene_facts(const RenderContext& ctx);

// Watts, the mean of the RGB channels. A light's emitted power: point, spot, laser their power,
// a quad light pi L A (one side). A sun has none of its own: its power through the cross-section
// of the box `size` (meters) facing it.
double light_watts(const LightDesc& l, Vec3 size);
// The emissive triangles of an imported file (a mesh or gltf shape): pi L A per emitting face
// (both faces of a double-sided material), emission textures not counted.
double emissive_watts(const SceneDesc& s, const ShapeDesc& shape);

// A file whose lamps and emissive surfaces differ in power by more than this factor (either
// way) has one of them in the other unit, almost certainly (683 between cd and W/sr).
inline constexpr double kLightScaleSuspect = 200;

// One line per problem, each beginning "warning: ".
std::vector<std::string> scene_warnings(const RenderContext& ctx, const SceneFacts& facts);

}  // namespace sl
