#pragma once
// The BSDF of a parsed material, for the loops that will evaluate GGX materials (camera paths,
// photon bounces, the gather, direct light): built once per material, like the material table.
// Diffuse maps to Lambert; mirror and smooth dielectric stay specular events
// (core/scattering.h) and have no BSDF here.
#include <optional>

#include "config/scene_desc.h"
#include "core/bsdf/bsdf.h"

namespace sl {

inline std::optional<bsdf::Bsdf> bsdf_of(const MaterialDesc& d) {
    bsdf::Bsdf b;
    b.alpha = bsdf::alpha_of_roughness(d.roughness);
    b.ior = d.ior;
    switch (d.type) {
    case MaterialType::Mirror:
    case MaterialType::Dielectric:
        return std::nullopt;
    case MaterialType::Diffuse:
        b.kind = bsdf::Kind::Lambert;
        b.base = d.albedo;
        break;
    case MaterialType::Conductor:
        b.kind = bsdf::Kind::Conductor;
        b.base = d.reflectance;
        b.complex_ior = d.complex_ior;
        b.eta = d.eta;
        b.k = d.k;
        break;
    case MaterialType::RoughDielectric:
        b.kind = bsdf::Kind::RoughDielectric;
        break;
    case MaterialType::MetallicRoughness:
        b.kind = bsdf::Kind::MetallicRoughness;
        b.base = d.albedo;
        b.metallic = d.metallic;
        b.specular = d.specular;
        b.specular_color = d.specular_color;
        b.transmission = d.transmission;
        b.blender3_base = d.principled == PrincipledBase::Blender3;
        b = bsdf::cache_layer_averages(b);
        break;
    }
    return b;
}

}  // namespace sl
