#pragma once
// The scene and its settings as plain structs, validated and already in SI units (meters,
// nanoseconds, per-meter coefficients). Everything downstream reads only these.
// Filled by config/parse_scene.h; field defaults are the scene file's defaults for omitted keys
// (defaults are in meters: `units` scales only what the file says).
#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "foundation/timeline.h"
#include "foundation/vec3.h"

namespace sl {

struct MeshData;      // core/import/mesh_data.h: triangles loaded from a mesh file
struct InstancedMeshes;  // core/import/mesh_instances.h: meshes placed more than once
struct TextureImage;  // core/texture.h: decoded texels, linear RGB

struct CameraDesc {
    Vec3 position{0, 1, 3.5f};
    Vec3 look_at{0, 1, 0};
    Vec3 up{0, 1, 0};
    float vfov_deg = 40;
    int width = 256;
    int height = 256;
};

// Diffuse, Mirror and Dielectric are smooth or Lambertian surfaces; the GGX materials are
// evaluated by their BSDFs (core/bsdf/, built into core/material_table.h).
enum class MaterialType { Diffuse, Mirror, Dielectric, Conductor, RoughDielectric, MetallicRoughness };

// How metallic_roughness draws its diffuse base (docs/materials.md, "The diffuse base"):
// EnergyConserving (the default) caps it so that a white base never returns more light than
// arrives; Blender3 draws it as Blender 3.x's Cycles (Principled v1) does, uncapped, so that a
// render matches Blender 3.x's own where Cycles gains energy.
enum class PrincipledBase { EnergyConserving, Blender3 };

struct MaterialDesc {
    std::string name;
    MaterialType type = MaterialType::Diffuse;
    Vec3 albedo{0.8f};       // diffuse; metallic_roughness: the base colour
    Vec3 reflectance{1.0f};  // mirror; conductor: reflectance at normal incidence (F0)
    float ior = 1.5f;        // dielectric, rough_dielectric, metallic_roughness
    // GGX materials: roughness as glTF and Blender mean it (the distribution's alpha = roughness^2).
    float roughness = 0.5f;
    bool complex_ior = false;  // conductor: eta + i k rather than F0
    Vec3 eta{1.0f}, k;         // conductor with complex_ior
    float metallic = 0;        // metallic_roughness
    float specular = 1;        // metallic_roughness: scales the dielectric reflectance (glTF specularFactor)
    Vec3 specular_color{1.0f};  // metallic_roughness: tints it (glTF specularColorFactor)
    float transmission = 0;    // metallic_roughness: the share of the dielectric base that transmits
    int metallic_roughness_texture = -1;  // glTF: G scales roughness, B metallic (linear)
    PrincipledBase principled = PrincipledBase::EnergyConserving;  // metallic_roughness's base
    // From imported files (glTF, OBJ/MTL); the scene JSON sets none of these.
    int albedo_texture = -1;    // index into SceneDesc::textures; multiplies albedo
    Vec3 emission;              // W sr^-1 m^-2: the surface is an area light
    int emission_texture = -1;  // multiplies emission
    // A tangent-space normal map (glTF normalTexture, MTL norm): linear, texel c -> 2c - 1, x and
    // y times normal_scale; on diffuse and GGX surfaces (core/surface_material.h).
    int normal_texture = -1;
    float normal_scale = 1;
    bool double_sided = false;  // emission leaves both faces (else the front: counter-clockwise)
    bool emits() const { return !is_black(emission); }
};

enum class TextureWrap { Repeat, Clamp, MirroredRepeat };

// An image file used by a material, decoded when the scene is resolved (core/import).
struct TextureDesc {
    std::string file;  // path, or "file.glb#image3" for an image inside a glTF file
    bool srgb = true;  // colour textures are sRGB-encoded; decoded to linear on load
    TextureWrap wrap_s = TextureWrap::Repeat, wrap_t = TextureWrap::Repeat;
    std::shared_ptr<const TextureImage> image;
};

enum class ShapeType { Quad, Box, Sphere, Mesh, Gltf };

// How a glTF file's KHR_lights_punctual intensities are read. Photometric (the glTF spec):
// candela for point and spot lights, lux for directional ones, at 683 lm/W (W sr^-1 = cd / 683,
// W m^-2 = lux / 683). Radiometric: the numbers are W sr^-1 and W m^-2 already.
enum class LightUnits { Photometric, Radiometric };
inline constexpr double kLumensPerWatt = 683;

struct ShapeDesc {
    ShapeType type = ShapeType::Quad;
    int material = 0;  // index into SceneDesc::materials; -1: a mesh's own materials
    // quad
    Vec3 corner, edge1, edge2;
    // box
    Vec3 min, max;
    // sphere
    Vec3 center;
    float radius = 0;
    // mesh: absolute path (resolved against the scene file's folder); the transform is
    // applied as scale, then rotation (X, then Y, then Z, degrees), then translation (meters).
    // `scale` includes meters_per_unit: the OBJ's coordinates are in the scene file's units.
    std::string file;
    Vec3 translate;
    float scale = 1;
    Vec3 rotate_deg;
    // mesh, gltf: the file's triangles in scene space, filled by resolve_imports
    // (core/import/resolve_imports.h); shared, so that copying a SceneDesc stays cheap.
    std::shared_ptr<const MeshData> mesh;
    // mesh, gltf: what the file places more than once (a glTF mesh under several nodes, or a
    // file several entries name), held once in its own space and placed by transforms; null
    // when everything is in `mesh` (filled by resolve_imports, like `mesh`).
    std::shared_ptr<const InstancedMeshes> instances;
    // gltf: the units of its lights' intensities; empty: the command line's
    // --gltf-light-units, else photometric (core/import/resolve_imports.cpp)
    std::optional<LightUnits> light_units;
    // gltf: how its metallic-roughness materials draw their diffuse base; empty: the command
    // line's --gltf-principled, else energy-conserving (core/import/resolve_imports.cpp)
    std::optional<PrincipledBase> principled;
    // mesh, gltf: the lights the file brought, lights[first_light, first_light + light_count)
    // (filled by resolve_imports; for `info`'s per-file checks)
    int first_light = 0, light_count = 0;
};

enum class LightType { Point, Quad, Spot, Laser, Sun };


struct LightDesc {
    LightType type = LightType::Point;
    Vec3 position;              // point, spot, laser
    Vec3 corner, edge1, edge2;  // quad
    Vec3 direction{0, -1, 0};   // spot, laser, sun: where the light goes (unit length after validation)
    Vec3 power;                 // W: point, spot, laser
    Vec3 radiance;              // W sr^-1 m^-2: quad (front side = edge1 x edge2)
    float cone_deg = 30;        // spot: the cone's full opening angle (it reaches cone_deg / 2 from the axis)
    float radius = 0.002f;      // laser beam radius (m)
    Vec3 irradiance;            // W m^-2 on a plane facing the light: sun
    float angle_deg = 0.53f;    // sun: angular diameter (core/sun_light.h)
};

struct MediumDesc {
    bool present = false;
    Vec3 sigma_a, sigma_s;  // per meter
    float g = 0;
    bool has_bounds = false;
    Vec3 bounds_min, bounds_max;
};

struct TimeDesc {
    double start_ns = 0;
    double end_ns = 12;
    int frames = 48;
    double fps = 24;
    // Δ, the edges and the buckets: timeline_of(scene) below (foundation/timeline.h).
};

enum class EmissionMode { Constant, Pulse };

struct EmissionDesc {
    EmissionMode mode = EmissionMode::Constant;
    double width_ns = 0;  // pulse width as given; 0 (omitted) means one frame width Δ
    // The pulse width in frames, m = width_ns / Δ (validated to be whole by
    // Timeline::whole_frames), or 1 when width_ns is 0. Buckets are counted by
    // timeline_of(scene).pulse_buckets, which reads this.
    int width_frames = 1;
};

struct RenderDesc {
    int passes = 64;
    int64_t photons_per_pass = 200000;
    // Vertices a photon or camera path may take: a safety cap only. Russian roulette ends paths
    // (survival by albedo or reflectance from the third vertex on), so closed rooms converge:
    // a white room of albedo 0.9 loses 0.9^1000 of its light to it (docs/design.md).
    int max_depth = 1000;
    float radius = 0;  // initial gather radius in meters; 0 means automatic
    float alpha = 0.7f;
    bool camera_tof = false;
    uint64_t seed = 1;
    Vec3 ambient;
};

struct SceneDesc {
    std::string source;  // file path, or "<default>" for the built-in demo
    double meters_per_unit = 1;
    CameraDesc camera;
    std::vector<MaterialDesc> materials;
    std::vector<ShapeDesc> shapes;
    std::vector<LightDesc> lights;
    std::vector<TextureDesc> textures;
    bool imports_resolved = false;
    std::optional<CameraDesc> imported_camera;  // the first camera of an imported glTF file
    MediumDesc medium;
    TimeDesc time;
    EmissionDesc emission;
    RenderDesc render;
    // Every file the run reads (the scene file first, then meshes, .mtl, .bin, textures), so
    // that no output may be one of them. Importers append what they read.
    std::vector<std::string> input_files;
};

// The scene's time axis: the parsed numbers handed to the Timeline, which alone computes with
// them (a pulse spans width_frames buckets; constant emission, one).
inline Timeline timeline_of(const SceneDesc& s) {
    Timeline t;
    t.start_ns = s.time.start_ns;
    t.end_ns = s.time.end_ns;
    t.frames = s.time.frames;
    t.pulse_buckets = s.emission.mode == EmissionMode::Pulse ? std::max(1, s.emission.width_frames) : 1;
    return t;
}

}  // namespace sl
