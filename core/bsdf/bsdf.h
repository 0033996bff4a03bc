#pragma once
// The surface scattering functions, as one tagged struct and switches (no virtual call per
// photon): Lambertian, GGX conductor, rough dielectric (reflection and transmission, Walter et
// al. 2007) and glTF's metallic-roughness material. Everything is in the local shading frame
// (normal +z); wo points away from the surface towards where the light goes (the viewer),
// wi towards where it comes from. eval is f(wo, wi) without the cosine; sample returns wi with
// weight = f |cos wi| / pdf, computed from eval and pdf themselves so the three always agree.
//
// Sides: Lambert, conductor and metallic-roughness without transmission are two-sided (they
// reflect on whichever side wo lies; wi on the other side gives 0). The rough dielectric and
// metallic-roughness with transmission have an outside (+z) and an inside of index `ior`.
//
// Transport: camera paths carry radiance, photons carry flux (importance transport, Veach
// 1997 ch. 5): refraction scales radiance by the squared ratio of indices and flux not, so
// transmission's f differs by that factor between the two (f_importance(wo, wi) = f_radiance(wi, wo)).
// Blender 3.x's glass (principled_v1_glass.h) differs between them also in the direction its one
// Fresnel reads, so pdf and sample take the mode too.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "core/bsdf/fresnel.h"
#include "core/bsdf/ggx.h"
#include "core/bsdf/microfacet.h"
#include "core/bsdf/principled_v1_glass.h"
#include "foundation/constants.h"
#include "foundation/vec3.h"

namespace sl::bsdf {

enum class Kind : uint8_t { Lambert, Conductor, RoughDielectric, MetallicRoughness };

struct Bsdf {
    Kind kind = Kind::Lambert;
    Vec3 base{0.8f};         // Lambert: albedo; conductor: F0 (Schlick); metallic-roughness: base colour
    Vec3 eta, k;             // conductor with a complex index (when complex_ior)
    bool complex_ior = false;
    // Metallic-roughness: the diffuse base and the glass (transmission) as Blender 3.x's Cycles
    // draws them, without the energy-conserving cap (mr_diffuse) and with Cycles 3.4's glass
    // (principled_v1_glass.h) ("principled": "blender3").
    bool blender3_base = false;
    float alpha = 0.25f;     // GGX alpha (roughness^2)
    float ior = 1.5f;        // rough dielectric, metallic-roughness: index inside / outside
    float metallic = 0;      // metallic-roughness
    float specular = 1;      // metallic-roughness: scales the dielectric reflectance (glTF specularFactor)
    Vec3 specular_color{1};  // metallic-roughness: tints it (glTF specularColorFactor)
    float transmission = 0;  // metallic-roughness: the share of the dielectric base that transmits
    // Metallic-roughness: the cosine-weighted hemispherical average of the layer's share
    // (layer_share) from outside and from inside, cached by cache_layer_averages for alpha
    // layer_avg_alpha (else computed when needed). Depends on ior, specular, its colour and alpha.
    float layer_avg_out = -1, layer_avg_in = -1, layer_avg_alpha = -1;
    // Metallic-roughness without transmission: one of its two lobes left out (evaluated,
    // drawn and its density counted as zero). Camera paths take a smooth coat's reflection by
    // following it and the diffuse base by the gather (camera_pass.cpp): the two halves of one
    // surface.
    bool no_diffuse = false, no_specular = false;
};

struct Sample {
    Vec3 wi;
    Vec3 weight;    // f |cos wi| / pdf
    float pdf = 0;  // solid-angle density of wi
    bool valid = false;
};

// --- helpers ---------------------------------------------------------------------------------

inline float luminance(Vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// Metallic-roughness: the probabilities of its three lobes (specular reflection, diffuse,
// transmission) at wo (wo.z > 0 in the frame it is evaluated in), from their albedos' rough sizes.
struct LobeChoice { float spec, diffuse, trans; };

inline float dielectric_scale(const Bsdf& b) { return std::clamp(b.specular * average(b.specular_color), 0.0f, 1.0f); }

inline Vec3 mr_specular_fresnel(const Bsdf& b, float cos_h, float eta) {
    const Vec3 metal = fresnel_schlick(b.base, cos_h);
    const Vec3 diel = vmin(b.specular_color * (b.specular * fresnel_dielectric(cos_h, eta)), Vec3(1));
    return metal * b.metallic + diel * (1 - b.metallic);
}

// The dielectric layer's reflectance at cos (its largest channel): the share of the light it
// keeps from the diffuse base, arriving or leaving at that angle.
inline float layer_fresnel(const Bsdf& b, float cos, float eta) {
    return max_component(vmin(b.specular_color * (b.specular * fresnel_dielectric(cos, eta)), Vec3(1)));
}

// What the rough layer takes from the diffuse base at cos: the smooth interface's reflectance,
// but never read beyond the grazing cosine roughness^1.5 / 2. A rough layer's own albedo E(mu)
// stays far below the smooth Fresnel curve near grazing (roughness 0.5 at 85 degrees: E 0.18,
// F 0.60, single-scattering GGX measured by quadrature), and F at that clamped cosine follows E
// from above (tests/bsdf: the white furnace).
inline float layer_cutoff(const Bsdf& b) { return 0.5f * std::pow(b.alpha, 0.75f); }
inline float layer_share(const Bsdf& b, float cos, float eta) {
    return layer_fresnel(b, std::max(std::abs(cos), layer_cutoff(b)), eta);
}

// 2 int_0^1 layer_share(mu) mu dmu: constant below the cutoff mu_0 (and below a critical
// cosine mu_c from inside, eta < 1: total reflection), smooth above, by 16-point Gauss-Legendre.
inline float layer_share_average(const Bsdf& b, float eta) {
    static constexpr double kX[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
                                     0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499};
    static constexpr double kW[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025, 0.1495959888165767,
                                     0.1246289712555339, 0.0951585116824928, 0.0622535239386479, 0.0271524594117541};
    const double mu_0 = layer_cutoff(b);
    const double mu_c = eta < 1 ? std::sqrt(1.0 - double(eta) * eta) : 0.0;
    const double lo = std::min(1.0, std::max(mu_0, mu_c));
    double sum = lo * lo * layer_share(b, static_cast<float>(mu_0), eta);
    for (int i = 0; i < 8; ++i)
        for (double sgn : {-1.0, 1.0}) {
            const double mu = lo + (1 - lo) * 0.5 * (1 + sgn * kX[i]);  // [-1, 1] -> [lo, 1]
            sum += kW[i] * 0.5 * (1 - lo) * 2 * mu * layer_share(b, static_cast<float>(mu), eta);
        }
    return static_cast<float>(sum);
}

// Caches both averages for the Bsdf's own alpha (eval recomputes them for any other alpha, as
// a roughness texture would give).
inline Bsdf cache_layer_averages(Bsdf b) {
    if (b.kind == Kind::MetallicRoughness) {
        b.layer_avg_out = layer_share_average(b, b.ior);
        b.layer_avg_in = layer_share_average(b, 1 / b.ior);
        b.layer_avg_alpha = b.alpha;
    }
    return b;
}

// For the side of index ratio eta = b.ior (the frame's +z: eval mirrors the frame and swaps
// the two cached values for a wo inside).
inline float layer_average(const Bsdf& b) {
    return b.layer_avg_out >= 0 && b.layer_avg_alpha == b.alpha ? b.layer_avg_out : layer_share_average(b, b.ior);
}

// Burley's diffuse shape ("Physically Based Shading at Disney", 2012, in the form Cycles 3.4's
// Principled v1 evaluates it, bsdf_principled_diffuse.h): darker than Lambert's towards grazing
// for smooth surfaces, brighter (retro-reflection) for rough ones. Symmetric in o and i.
inline float burley(float cos_o, float cos_i, float cos_oi, float roughness) {
    auto schlick_weight = [](float c) {
        const float m = std::clamp(1 - c, 0.0f, 1.0f), m2 = m * m;
        return m2 * m2 * m;
    };
    const float fo = schlick_weight(cos_o), fi = schlick_weight(cos_i);
    const float rr = roughness * (1 + cos_oi);  // 2 roughness cos^2 of the half angle
    return (1 - 0.5f * fo) * (1 - 0.5f * fi) + rr * (fo + fi + fo * fi * (rr - 1));
}

// The diffuse base of metallic-roughness, f without the 1/pi and the (1 - metallic)
// (1 - transmission) weight, per channel (docs/materials.md, "The diffuse base"): the base colour
// as Blender's Principled BSDF (Cycles 3.4, v1) adds it under its specular layer: undimmed by the
// layer, with Burley's shape; but never more than (1 - S(o))(1 - S(i)) / (1 - average S), S the
// layer's share above, the energy-conserving share the layer leaves (Kelemen & Szirmay-Kalos
// 2001). With that cap a white base's albedo is at most E_layer(o) + 1 - S(o) <= 1 wherever S
// stays above the layer's own albedo E (tests/bsdf: the white furnaces). Symmetric in o and i:
// reciprocal. For Blender's default layer
// the cap does not bite below a base of ~0.6 (roughness 0.5). A material without a layer
// (specular 0) is Lambertian: what glTF means, and what the OBJ/JSON diffuse surfaces are.
// blender3_base drops the cap: base x Burley's shape exactly as Cycles 3.x adds it, which
// returns more light than arrives where the layer and a bright base meet near grazing (the
// user asked for Blender 3.x's render, not for glTF's energy balance). Still reciprocal.
inline Vec3 mr_diffuse(const Bsdf& b, Vec3 wo, Vec3 wi) {
    // Without a layer (specular 0) the surface is the Lambertian one glTF means (and the cap is 1).
    const bool layered = b.specular * max_component(b.specular_color) > 0;
    const float shape = layered ? burley(wo.z, wi.z, dot(wo, wi), std::sqrt(b.alpha)) : 1.0f;
    if (b.blender3_base) return b.base * shape;
    const float cap = (1 - layer_share(b, wo.z, b.ior)) * (1 - layer_share(b, wi.z, b.ior)) /
                      std::max(1e-6f, 1 - layer_average(b));
    return vmin(b.base * shape, Vec3(cap));
}

inline LobeChoice mr_lobes(const Bsdf& b, Vec3 wo, float eta) {
    const float fo = dielectric_scale(b) * fresnel_dielectric(wo.z, eta);
    const float base = std::max(0.0f, luminance(b.base));
    float s = b.metallic * luminance(fresnel_schlick(b.base, wo.z)) + (1 - b.metallic) * luminance(
                  vmin(b.specular_color * (b.specular * fresnel_dielectric(wo.z, eta)), Vec3(1)));
    float d = (1 - b.metallic) * (1 - b.transmission) * base * (1 - fo);
    // Not (1 - fo) alone: beyond the critical angle of the macro-surface (fo = 1) microfacets
    // tilted towards wo still transmit, so the lobe must keep a chance of being drawn.
    float t = (1 - b.metallic) * b.transmission * base * std::max(0.25f, 1 - fo);
    if (b.no_specular) s = 0;
    if (b.no_diffuse) d = 0;
    const float sum = s + d + t;
    if (!(sum > 0)) return {0, 0, 0};
    return {s / sum, d / sum, t / sum};
}

// Metallic-roughness with transmission: a drawn microfacet reflects with this probability and
// transmits otherwise, its reflectance against its transmittance at the microfacet (cos_h =
// wo.m), as a rough dielectric chooses by F(wo.m). Choosing instead by the lobes' shares at the
// macro-surface gave weights above 1: inside beyond the critical angle every microfacet that
// reflects (F = 1) was drawn with probability 0.8, a weight of 1.25 per internal reflection,
// which compounded (x1.25^k) into fireflies through solid glass.
inline float mr_reflect_share(const Bsdf& b, float cos_h, float eta) {
    const float r = luminance(mr_specular_fresnel(b, cos_h, eta));
    const float t = (1 - b.metallic) * b.transmission * (1 - dielectric_scale(b) * fresnel_dielectric(cos_h, eta)) *
                    std::max(0.0f, luminance(b.base));
    return r + t > 0 ? r / (r + t) : 1.0f;
}

// Blender 3.x's glass (blender3_base with transmission, principled_v1_glass.h): the glass
// closure's weight (1 - metallic) transmission; the specular layer keeps the rest.
inline bool v1_glass(const Bsdf& b) {
    return b.kind == Kind::MetallicRoughness && b.blender3_base && b.transmission > 0;
}
inline float v1_glass_weight(const Bsdf& b) { return (1 - b.metallic) * b.transmission; }

// Its lobe choice at wo (wo.z > 0): the specular layer, the diffuse base and the glass by their
// rough albedos at wo. The glass keeps at least a tenth of its weight: photons read its Fresnel
// at wi, and a black base still reflects.
inline LobeChoice v1_lobes(const Bsdf& b, Vec3 wo, float eta) {
    const float wg = v1_glass_weight(b), f = fresnel_dielectric(wo.z, eta), base = std::max(0.0f, luminance(b.base));
    const float s = (1 - wg) * luminance(mr_specular_fresnel(b, wo.z, eta));
    const float d = (1 - b.metallic) * (1 - b.transmission) * base;
    const float t = wg * std::max(0.1f, f + (1 - f) * base);
    const float sum = s + d + t;
    if (!(sum > 0)) return {0, 0, 0};
    return {s / sum, d / sum, t / sum};
}

// --- eval ------------------------------------------------------------------------------------

// The frame a BSDF is evaluated in: two-sided kinds mirror both directions when wo is below.
inline bool two_sided(const Bsdf& b) {
    return b.kind == Kind::Lambert || b.kind == Kind::Conductor ||
           (b.kind == Kind::MetallicRoughness && b.transmission <= 0);
}

inline Vec3 eval(const Bsdf& b, Vec3 wo, Vec3 wi, Transport mode = Transport::Radiance) {
    if (wo.z == 0 || wi.z == 0) return Vec3(0);
    if (wo.z < 0 && b.kind != Kind::RoughDielectric) {
        if (two_sided(b) || b.kind == Kind::MetallicRoughness) {
            // Metallic-roughness with transmission: the inside sees the interface of index 1/ior.
            Bsdf inv = b;
            if (!two_sided(b)) {
                inv.ior = 1 / b.ior;
                std::swap(inv.layer_avg_out, inv.layer_avg_in);
            }
            wo.z = -wo.z;
            wi.z = -wi.z;
            return eval(inv, wo, wi, mode);
        }
    }
    const Ggx g{b.alpha};
    Vec3 wm;
    switch (b.kind) {
    case Kind::Lambert:
        return wi.z > 0 ? b.base * (1 / kPi) : Vec3(0);
    case Kind::Conductor: {
        const float lobe = ggx_reflection(g, wo, wi, wm);
        if (lobe == 0) return Vec3(0);
        const float c = dot(wo, wm);
        return (b.complex_ior ? fresnel_conductor(c, b.eta, b.k) : fresnel_schlick(b.base, c)) * lobe;
    }
    case Kind::RoughDielectric: {
        if (wo.z * wi.z > 0) {  // reflection, on either side
            const float s = wo.z > 0 ? 1.0f : -1.0f;
            const Vec3 o{wo.x, wo.y, wo.z * s}, i{wi.x, wi.y, wi.z * s};
            const float lobe = ggx_reflection(g, o, i, wm);
            return Vec3(lobe == 0 ? 0 : lobe * fresnel_dielectric(dot(o, wm), s > 0 ? b.ior : 1 / b.ior));
        }
        const float etap = wo.z > 0 ? b.ior : 1 / b.ior;
        if (!refraction_half_vector(wo, wi, etap, wm)) return Vec3(0);
        const float f = 1 - fresnel_dielectric(dot(wo, wm), b.ior);
        return Vec3(f * ggx_transmission(g, wo, wi, wm, etap, mode));
    }
    case Kind::MetallicRoughness: {
        // Here wo.z > 0; ior is the index across the interface from wo's side.
        if (v1_glass(b)) {  // Cycles 3.4: specular layer (1 - wg), diffuse, glass wg
            const float wg = v1_glass_weight(b);
            Vec3 f = v1_glass_eval(g, wo, wi, b.ior, b.base, mode) * wg;
            if (wi.z <= 0) return f;
            const float lobe = ggx_reflection(g, wo, wi, wm);
            if (lobe > 0) f += mr_specular_fresnel(b, dot(wo, wm), b.ior) * (lobe * (1 - wg));
            const float kd = (1 - b.metallic) * (1 - b.transmission);
            return kd > 0 ? f + mr_diffuse(b, wo, wi) * (kd / kPi) : f;
        }
        if (wi.z > 0) {
            const float lobe = b.no_specular ? 0.0f : ggx_reflection(g, wo, wi, wm);
            Vec3 f = lobe == 0 ? Vec3(0) : mr_specular_fresnel(b, dot(wo, wm), b.ior) * lobe;
            const float kd = b.no_diffuse ? 0.0f : (1 - b.metallic) * (1 - b.transmission);
            if (kd <= 0) return f;
            return f + mr_diffuse(b, wo, wi) * (kd / kPi);
        }
        if (b.transmission <= 0) return Vec3(0);
        if (!refraction_half_vector(wo, wi, b.ior, wm)) return Vec3(0);
        const float t = (1 - b.metallic) * b.transmission * (1 - dielectric_scale(b) * fresnel_dielectric(dot(wo, wm), b.ior));
        return b.base * (t * ggx_transmission(g, wo, wi, wm, b.ior, mode));
    }
    }
    return Vec3(0);
}

// --- pdf -------------------------------------------------------------------------------------

// mode: Blender 3.x's glass draws differently for photons (principled_v1_glass.h).
inline float pdf(const Bsdf& b, Vec3 wo, Vec3 wi, Transport mode = Transport::Radiance) {
    if (wo.z == 0 || wi.z == 0) return 0;
    if (wo.z < 0 && b.kind != Kind::RoughDielectric) {
        Bsdf inv = b;
        if (!two_sided(b)) inv.ior = 1 / b.ior;
        wo.z = -wo.z;
        wi.z = -wi.z;
        return pdf(inv, wo, wi, mode);
    }
    const Ggx g{b.alpha};
    Vec3 wm;
    switch (b.kind) {
    case Kind::Lambert:
        return wi.z > 0 ? wi.z / kPi : 0;
    case Kind::Conductor:
        return ggx_reflection(g, wo, wi, wm) > 0 ? ggx_reflection_pdf(g, wo, wm) : 0;
    case Kind::RoughDielectric: {
        if (wo.z * wi.z > 0) {
            const float s = wo.z > 0 ? 1.0f : -1.0f;
            const Vec3 o{wo.x, wo.y, wo.z * s}, i{wi.x, wi.y, wi.z * s};
            if (ggx_reflection(g, o, i, wm) == 0) return 0;
            return ggx_reflection_pdf(g, o, wm) * fresnel_dielectric(dot(o, wm), s > 0 ? b.ior : 1 / b.ior);
        }
        const float etap = wo.z > 0 ? b.ior : 1 / b.ior;
        if (!refraction_half_vector(wo, wi, etap, wm)) return 0;
        const float t = 1 - fresnel_dielectric(dot(wo, wm), b.ior);
        return ggx_transmission_pdf(g, wo, wi, wm, etap) * t;
    }
    case Kind::MetallicRoughness: {
        if (v1_glass(b)) {  // the specular layer and the glass's reflection share GGX's draw
            const LobeChoice p = v1_lobes(b, wo, b.ior);
            float r = p.trans * v1_glass_pdf(g, wo, wi, b.ior, mode);
            if (wi.z > 0) {
                if (ggx_reflection(g, wo, wi, wm) > 0) r += p.spec * ggx_reflection_pdf(g, wo, wm);
                r += p.diffuse * wi.z / kPi;
            }
            return r;
        }
        const LobeChoice p = mr_lobes(b, wo, b.ior);
        if (b.transmission > 0) {  // one microfacet draw for both, split at the microfacet
            const float pd = p.spec + p.trans;
            if (wi.z > 0) {
                float spec = 0;
                if (ggx_reflection(g, wo, wi, wm) > 0)
                    spec = ggx_reflection_pdf(g, wo, wm) * mr_reflect_share(b, dot(wo, wm), b.ior);
                return pd * spec + p.diffuse * wi.z / kPi;
            }
            if (pd <= 0 || !refraction_half_vector(wo, wi, b.ior, wm)) return 0;
            return pd * ggx_transmission_pdf(g, wo, wi, wm, b.ior) * (1 - mr_reflect_share(b, dot(wo, wm), b.ior));
        }
        if (wi.z > 0) {
            const float spec = ggx_reflection(g, wo, wi, wm) > 0 ? ggx_reflection_pdf(g, wo, wm) : 0;
            return p.spec * spec + p.diffuse * wi.z / kPi;
        }
        if (p.trans <= 0 || !refraction_half_vector(wo, wi, b.ior, wm)) return 0;
        return p.trans * ggx_transmission_pdf(g, wo, wi, wm, b.ior);
    }
    }
    return 0;
}

// --- sample ----------------------------------------------------------------------------------

// A direction wi for wo from three uniform numbers in [0, 1): uc picks a lobe (or reflection
// against refraction), (u1, u2) the direction. Invalid when the draw leaves the lobe (a
// reflected direction below the surface: the energy single-scattering GGX loses).
inline Sample sample(const Bsdf& b, Vec3 wo, float uc, float u1, float u2, Transport mode = Transport::Radiance) {
    Sample s;
    if (wo.z == 0) return s;
    const float side = wo.z > 0 ? 1.0f : -1.0f;  // the two-sided kinds sample in the mirrored frame
    const Vec3 o{wo.x, wo.y, wo.z * side};
    const Ggx g{b.alpha};
    Vec3 wi;
    auto finish = [&](Vec3 w) {
        s.pdf = pdf(b, wo, w, mode);
        if (!(s.pdf > 0)) return s;
        s.wi = w;
        s.weight = eval(b, wo, w, mode) * (std::abs(w.z) / s.pdf);
        s.valid = true;
        return s;
    };
    auto cosine = [&]() {
        const float r = std::sqrt(u1), phi = 2 * kPi * u2;
        return Vec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1 - u1)));
    };
    switch (b.kind) {
    case Kind::Lambert:
        wi = cosine();
        break;
    case Kind::Conductor:
        wi = reflect_about(o, g.sample_visible(o, u1, u2));
        if (wi.z <= 0) return s;
        break;
    case Kind::RoughDielectric: {
        const Vec3 wm = g.sample_visible(wo, u1, u2);  // z > 0
        const float r = fresnel_dielectric(dot(wo, wm), b.ior);
        if (uc < r) {
            wi = reflect_about(wo, wm);
            if (wi.z * wo.z <= 0) return s;  // reflected through the macro-surface: lost
        } else {
            float etap;
            if (!refract_about(wo, wm, b.ior, wi, etap) || wi.z * wo.z >= 0) return s;
        }
        if (!is_finite(wi)) return s;
        return finish(wi);  // this kind samples in its own (unmirrored) frame
    }
    case Kind::MetallicRoughness: {
        const float eta = (two_sided(b) || side > 0) ? b.ior : 1 / b.ior;
        if (v1_glass(b)) {
            const LobeChoice p = v1_lobes(b, o, eta);
            if (p.spec + p.diffuse + p.trans <= 0) return s;
            if (uc < p.diffuse) {
                wi = cosine();
            } else if (uc < p.diffuse + p.spec) {
                wi = reflect_about(o, g.sample_visible(o, u1, u2));
                if (wi.z <= 0) return s;  // reflected through the macro-surface: lost
            } else if (!v1_glass_sample(g, o, eta, mode, (uc - p.diffuse - p.spec) / p.trans, u1, u2, wi)) {
                return s;
            }
            break;
        }
        const LobeChoice p = mr_lobes(b, o, eta);
        if (p.spec + p.diffuse + p.trans <= 0) return s;
        if (!two_sided(b)) {  // with transmission: diffuse, or a microfacet that reflects or transmits
            if (uc < p.diffuse) {
                wi = cosine();
            } else {
                const Vec3 wm = g.sample_visible(o, u1, u2);
                const float uf = (uc - p.diffuse) / (p.spec + p.trans);
                if (uf < mr_reflect_share(b, dot(o, wm), eta)) {
                    wi = reflect_about(o, wm);
                    if (wi.z <= 0) return s;  // reflected through the macro-surface: lost
                } else {
                    float etap;
                    if (!refract_about(o, wm, eta, wi, etap) || wi.z >= 0) return s;
                }
            }
        } else if (uc < p.spec) {
            wi = reflect_about(o, g.sample_visible(o, u1, u2));
            if (wi.z <= 0) return s;  // reflected through the macro-surface: lost
        } else if (uc < p.spec + p.diffuse) {
            wi = cosine();
        } else {
            float etap;
            if (!refract_about(o, g.sample_visible(o, u1, u2), eta, wi, etap) || wi.z >= 0) return s;
        }
        break;
    }
    }
    wi.z *= side;
    if (wi.z == 0 || !is_finite(wi)) return s;
    return finish(wi);
}

}  // namespace sl::bsdf
