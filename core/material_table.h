#pragma once
// The materials as the tracers read them at a hit, built once from the parsed scene (as the
// geometry and the lights are): the parsed MaterialDesc keeps names and texture indices for
// the parser and the importers, this keeps only what a bounce needs, with the textures already
// resolved to their decoded images. The values are copied unchanged, so every image is the
// same as when the loops read the parsed structs.
#include <cstddef>
#include <vector>

#include "config/scene_desc.h"
#include "core/bsdf/material_bsdf.h"
#include "core/texture.h"

namespace sl {

// How camera paths treat a GGX surface (docs/materials.md, "In the renderer"): they follow a
// sampled direction through glossy ones (smooth enough that a photon estimate would blur them,
// or with an inside: rough glass), and end on the others with a visible point that weighs
// direct light and photons by the BSDF. Photons are stored only where visible points may be.
enum class GlossyUse : uint8_t { None, Follow, Gather };

// Below this roughness a conductor (or a pure metal) is followed by camera paths.
inline constexpr float kFollowBelowRoughness = 0.5f;

struct SurfaceMaterial {
    MaterialType type = MaterialType::Diffuse;
    Vec3 albedo;       // diffuse (and metallic-roughness: the base colour its texture multiplies)
    Vec3 reflectance;  // mirror
    float ior = 1.5f;  // dielectric, rough dielectric, metallic-roughness with transmission
    Vec3 emission;     // W sr^-1 m^-2: the surface is an area light
    const TextureImage* albedo_texture = nullptr;    // multiplies albedo
    const TextureImage* emission_texture = nullptr;  // multiplies emission
    // Metallic-roughness: G scales `roughness`, B the BSDF's metallic (glTF), per hit.
    const TextureImage* metallic_roughness_texture = nullptr;
    float roughness = 0.5f;  // GGX kinds: the factor the texture scales
    // Tangent-space normal map (core/surface_material.h); none on a mirror or smooth glass,
    // whose reflection and refraction use the geometric normal.
    const TextureImage* normal_texture = nullptr;
    float normal_scale = 1;
    bool double_sided = false;  // emission leaves both faces (else the front)
    // GGX kinds (conductor, rough dielectric, metallic-roughness): their BSDF and how camera
    // paths use it.
    GlossyUse glossy = GlossyUse::None;
    bsdf::Bsdf bsdf;
    bool emits() const { return !is_black(emission); }
};

// A metallic-roughness surface by its numbers (the material's factors, or at a hit its
// textured values: core/glossy_path.h).
inline GlossyUse metallic_roughness_use(float metallic, float roughness, float transmission) {
    if (transmission > 0) return GlossyUse::Follow;  // it has an inside, as glass does
    // A metal has no diffuse base: like a conductor. Anything with a diffuse base gathers.
    return metallic >= 1 && roughness < kFollowBelowRoughness ? GlossyUse::Follow : GlossyUse::Gather;
}

inline GlossyUse glossy_use(const MaterialDesc& d) {
    switch (d.type) {
    case MaterialType::Diffuse:
    case MaterialType::Mirror:
    case MaterialType::Dielectric:
        return GlossyUse::None;
    case MaterialType::RoughDielectric:
        return GlossyUse::Follow;
    case MaterialType::Conductor:
        return d.roughness < kFollowBelowRoughness ? GlossyUse::Follow : GlossyUse::Gather;
    case MaterialType::MetallicRoughness:
        return metallic_roughness_use(d.metallic, d.roughness, d.transmission);
    }
    return GlossyUse::None;
}

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
            SurfaceMaterial m;
            m.type = d.type;
            m.albedo = d.albedo;
            m.reflectance = d.reflectance;
            m.ior = d.ior;
            m.emission = d.emission;
            m.albedo_texture = image(d.albedo_texture);
            m.emission_texture = image(d.emission_texture);
            m.double_sided = d.double_sided;
            m.roughness = d.roughness;
            if (d.type != MaterialType::Mirror && d.type != MaterialType::Dielectric) {
                m.normal_texture = image(d.normal_texture);
                m.normal_scale = d.normal_scale;
            }
            m.glossy = glossy_use(d);
            if (m.glossy != GlossyUse::None) {
                m.bsdf = *bsdf_of(d);
                // Only the metallic-roughness material has textures (base colour, metallic-roughness).
                if (d.type == MaterialType::MetallicRoughness)
                    m.metallic_roughness_texture = image(d.metallic_roughness_texture);
                else
                    m.albedo_texture = nullptr;
            }
            materials_.push_back(m);
        }
    }
    const SurfaceMaterial& operator[](int i) const { return materials_[static_cast<size_t>(i)]; }
    size_t size() const { return materials_.size(); }

private:
    std::vector<SurfaceMaterial> materials_;
};

}  // namespace sl
