#pragma once
// The materials as the tracers read them at a hit, built once from the parsed scene (as the
// geometry and the lights are): the parsed MaterialDesc keeps names and texture indices for
// the parser and the importers, this keeps only what a bounce needs, with the textures already
// resolved to their decoded images. The values are copied unchanged, so every image is the
// same as when the loops read the parsed structs.
#include <cstddef>
#include <vector>

#include "config/scene_desc.h"
#include "core/material_stand_in.h"
#include "core/texture.h"

namespace sl {

struct SurfaceMaterial {
    MaterialType type = MaterialType::Diffuse;  // Diffuse, Mirror or Dielectric (core/material_stand_in.h)
    Vec3 albedo;       // diffuse
    Vec3 reflectance;  // mirror
    float ior = 1.5f;  // dielectric
    Vec3 emission;     // W sr^-1 m^-2: the surface is an area light
    const TextureImage* albedo_texture = nullptr;    // multiplies albedo
    const TextureImage* emission_texture = nullptr;  // multiplies emission
    bool double_sided = false;  // emission leaves both faces (else the front)
    bool emits() const { return !is_black(emission); }
};

class MaterialTable {
public:
    MaterialTable() = default;
    // `scene` has its imports resolved: its textures are decoded (and must outlive the table).
    explicit MaterialTable(const SceneDesc& scene) {
        auto image = [&](int index) -> const TextureImage* {
            return index < 0 ? nullptr : scene.textures[static_cast<size_t>(index)].image.get();
        };
        materials_.reserve(scene.materials.size());
        for (const MaterialDesc& d : scene.materials) {
            const StandIn s = stand_in(d);  // a GGX material as one of the three surfaces
            materials_.push_back({s.type, s.albedo, s.reflectance, s.ior, d.emission, image(d.albedo_texture),
                                  image(d.emission_texture), d.double_sided});
        }
    }
    const SurfaceMaterial& operator[](int i) const { return materials_[static_cast<size_t>(i)]; }
    size_t size() const { return materials_.size(); }

private:
    std::vector<SurfaceMaterial> materials_;
};

}  // namespace sl
