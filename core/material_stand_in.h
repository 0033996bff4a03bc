#pragma once
// How the estimator draws a GGX material today. Camera paths, photon bounces and direct light
// evaluate three surfaces (Lambertian, perfect mirror, smooth dielectric); a conductor, a rough
// dielectric or a glTF metallic-roughness material is drawn as the nearest of those until they
// evaluate its BSDF (core/bsdf/bsdf.h, built by core/bsdf/material_bsdf.h). The rules are the
// glTF importer's of before the GGX materials existed, so every scene renders as it did:
//   metallic-roughness: transmission > 0.5 -> smooth glass; metallic >= 0.9 and roughness <= 0.1
//     -> mirror of the base colour; else diffuse with the base colour (the specular layer of a
//     dielectric base is dropped; a metal base is drawn matte);
//   conductor: roughness <= 0.1 -> mirror of F0; else diffuse with F0;
//   rough dielectric: smooth glass.
// approximation_note says, in one phrase, what such a stand-in loses (empty: nothing a user
// would see: Blender's default Principled and Emission-only materials give none).
#include <string>

#include "config/scene_desc.h"
#include "core/bsdf/fresnel.h"

namespace sl {

inline constexpr float kStandInMaxMirrorRoughness = 0.1f;

struct StandIn {
    MaterialType type = MaterialType::Diffuse;  // Diffuse, Mirror or Dielectric
    Vec3 albedo, reflectance;
    float ior = 1.5f;
};

// A conductor's reflectance at normal incidence.
inline Vec3 conductor_f0(const MaterialDesc& d) {
    if (!d.complex_ior) return d.reflectance;
    return bsdf::fresnel_conductor(1, d.eta, d.k);
}

inline StandIn stand_in(const MaterialDesc& d) {
    StandIn s{d.type, d.albedo, d.reflectance, d.ior};
    switch (d.type) {
    case MaterialType::Diffuse:
    case MaterialType::Mirror:
    case MaterialType::Dielectric:
        break;
    case MaterialType::Conductor:
        s.reflectance = s.albedo = conductor_f0(d);
        s.type = d.roughness <= kStandInMaxMirrorRoughness ? MaterialType::Mirror : MaterialType::Diffuse;
        break;
    case MaterialType::RoughDielectric:
        s.type = MaterialType::Dielectric;
        break;
    case MaterialType::MetallicRoughness:
        s.reflectance = d.albedo;
        if (d.transmission > 0.5f) s.type = MaterialType::Dielectric;
        else if (d.metallic >= 0.9f && d.roughness <= kStandInMaxMirrorRoughness) s.type = MaterialType::Mirror;
        else s.type = MaterialType::Diffuse;
        break;
    }
    return s;
}

inline std::string approximation_note(const MaterialDesc& d) {
    const auto r = [&] { return std::to_string(d.roughness).substr(0, 4); };
    const StandIn s = stand_in(d);
    switch (d.type) {
    case MaterialType::Diffuse:
    case MaterialType::Mirror:
    case MaterialType::Dielectric:
        return "";
    case MaterialType::Conductor:
        return s.type == MaterialType::Diffuse
                   ? "rough metal (roughness " + r() + ") is drawn diffuse with its reflectance at normal incidence"
                   : "";
    case MaterialType::RoughDielectric:
        return d.roughness > kStandInMaxMirrorRoughness ? "rough glass (roughness " + r() + ") is drawn smooth" : "";
    case MaterialType::MetallicRoughness: {
        std::string n;
        const auto add = [&](const std::string& x) { n += (n.empty() ? "" : "; ") + x; };
        if (s.type == MaterialType::Dielectric) {
            if (d.albedo_texture >= 0 || max_component(Vec3(1) - d.albedo) > 0.01f)
                add("the glass is clear: base colour and its texture are ignored");
            if (d.roughness > kStandInMaxMirrorRoughness) add("rough glass is drawn smooth");
        } else if (s.type == MaterialType::Mirror) {
            if (d.albedo_texture >= 0) add("a mirror keeps no texture (base colour factor only)");
        } else {
            // A black base reflects nothing as a metal or as a diffuse surface: nothing is lost
            // (Blender writes an Emission-only material so: black, metallic 1 by default).
            const bool black = is_black(d.albedo) && d.albedo_texture < 0;
            if (d.metallic >= 0.9f && !black) add("rough metal (roughness " + r() + ") is drawn diffuse with the base colour");
            else if (d.metallic > 0.1f && !black) add("partly metallic: drawn diffuse with the base colour");
            if (d.transmission > 0) add("partial transmission is ignored");
        }
        return n;
    }
    }
    return "";
}

}  // namespace sl
