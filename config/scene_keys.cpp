#include "config/scene_keys.h"

#include <stdexcept>
#include <string>

namespace sl {

namespace {

using K = const std::string_view[];

constexpr K kTop = {"units", "camera", "materials", "shapes", "lights", "medium", "time", "emission", "render"};
constexpr K kUnits = {"meters_per_unit"};
constexpr K kCamera = {"position", "look_at", "up", "vfov_deg", "width", "height"};
constexpr K kDiffuse = {"type", "albedo", "emission"};
constexpr K kMirror = {"type", "reflectance", "emission"};
constexpr K kDielectric = {"type", "ior", "emission"};
constexpr K kConductor = {"type", "reflectance", "eta", "k", "roughness", "emission"};
constexpr K kRoughDielectric = {"type", "ior", "roughness", "emission"};
constexpr K kMetallicRoughness = {"type", "base_color", "metallic", "roughness", "ior", "specular", "transmission", "principled", "emission"};
constexpr K kQuadShape = {"type", "corner", "edge1", "edge2", "material"};
constexpr K kBox = {"type", "min", "max", "material"};
constexpr K kSphere = {"type", "center", "radius", "material"};
constexpr K kMesh = {"type", "file", "translate", "scale", "rotate_deg", "material"};
constexpr K kGltf = {"type", "file", "translate", "scale", "rotate_deg", "material", "light_units", "principled"};
constexpr K kPoint = {"type", "position", "power"};
constexpr K kQuadLight = {"type", "corner", "edge1", "edge2", "radiance"};
constexpr K kSpot = {"type", "position", "direction", "cone_deg", "power"};
constexpr K kLaser = {"type", "position", "direction", "radius", "power"};
constexpr K kSun = {"type", "direction", "angle_deg", "irradiance", "radiance"};
constexpr K kMedium = {"sigma_a", "sigma_s", "g", "bounds"};
constexpr K kBounds = {"min", "max"};
constexpr K kTime = {"start_ns", "end_ns", "frames", "fps"};
constexpr K kEmission = {"mode", "width_ns"};
constexpr K kRender = {"passes", "photons_per_pass", "max_depth", "radius", "alpha", "camera_tof", "seed", "ambient"};

const SceneObjectKeys kObjects[] = {
    {"", "", kTop},
    {"units", "", kUnits},
    {"camera", "", kCamera},
    {"materials", "diffuse", kDiffuse},
    {"materials", "mirror", kMirror},
    {"materials", "dielectric", kDielectric},
    {"materials", "conductor", kConductor},
    {"materials", "rough_dielectric", kRoughDielectric},
    {"materials", "metallic_roughness", kMetallicRoughness},
    {"shapes", "quad", kQuadShape},
    {"shapes", "box", kBox},
    {"shapes", "sphere", kSphere},
    {"shapes", "mesh", kMesh},
    {"shapes", "gltf", kGltf},
    {"lights", "point", kPoint},
    {"lights", "quad", kQuadLight},
    {"lights", "spot", kSpot},
    {"lights", "laser", kLaser},
    {"lights", "sun", kSun},
    {"medium", "", kMedium},
    {"medium.bounds", "", kBounds},
    {"time", "", kTime},
    {"emission", "", kEmission},
    {"render", "", kRender},
};

}  // namespace

std::span<const SceneObjectKeys> scene_object_keys() { return kObjects; }

std::span<const std::string_view> scene_keys_of(std::string_view object, std::string_view type) {
    for (const SceneObjectKeys& o : kObjects)
        if (o.object == object && o.type == type) return o.keys;
    throw std::logic_error("scene_keys_of: no key list for '" + std::string(object) + "' of type '" +
                           std::string(type) + "'");
}

}  // namespace sl
