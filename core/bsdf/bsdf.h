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
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/bsdf/fresnel.h"
#include "core/bsdf/ggx.h"
#include "foundation/constants.h"
#include "foundation/vec3.h"

namespace sl::bsdf {

enum class Kind : uint8_t { Lambert, Conductor, RoughDielectric, MetallicRoughness };
enum class Transport : uint8_t { Radiance, Importance };

struct Bsdf {
    Kind kind = Kind::Lambert;
    Vec3 base{0.8f};         // Lambert: albedo; conductor: F0 (Schlick); metallic-roughness: base colour
    Vec3 eta, k;             // conductor with a complex index (when complex_ior)
    bool complex_ior = false;
    float alpha = 0.25f;     // GGX alpha (roughness^2)
    float ior = 1.5f;        // rough dielectric, metallic-roughness: index inside / outside
    float metallic = 0;      // metallic-roughness
    float specular = 1;      // metallic-roughness: scales the dielectric reflectance (glTF specularFactor)
    Vec3 specular_color{1};  // metallic-roughness: tints it (glTF specularColorFactor)
    float transmission = 0;  // metallic-roughness: the share of the dielectric base that transmits
};

struct Sample {
    Vec3 wi;
    Vec3 weight;    // f |cos wi| / pdf
    float pdf = 0;  // solid-angle density of wi
    bool valid = false;
};

// --- helpers ---------------------------------------------------------------------------------

inline Vec3 reflect_about(Vec3 wo, Vec3 n) { return n * (2 * dot(wo, n)) - wo; }

// Refraction of wo through a surface of normal n (wo on either side); eta = n_other / n_wo-side
// relative to n's side. False on total internal reflection. etap: the index ratio used.
inline bool refract_about(Vec3 wo, Vec3 n, float eta, Vec3& wt, float& etap) {
    float cos_i = dot(n, wo);
    if (cos_i < 0) { eta = 1 / eta; cos_i = -cos_i; n = -n; }
    const float sin2_t = std::max(0.0f, 1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1) return false;
    const float cos_t = std::sqrt(1 - sin2_t);
    wt = -wo / eta + n * (cos_i / eta - cos_t);
    etap = eta;
    return true;
}

inline float luminance(Vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// The GGX reflection lobe without Fresnel: D G2 / (4 cos_o cos_i), and its sampling density
// (both directions on the +z side).
inline float ggx_reflection(const Ggx& g, Vec3 wo, Vec3 wi, Vec3& wm) {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    wm = wo + wi;
    if (dot(wm, wm) == 0) return 0;
    wm = normalize(wm);
    return g.d(wm) * g.g2(wo, wi) / (4 * wo.z * wi.z);
}
inline float ggx_reflection_pdf(const Ggx& g, Vec3 wo, Vec3 wm) {
    const float c = dot(wo, wm);
    return c > 0 ? g.d_visible(wo, wm) / (4 * c) : 0;
}

// The half vector of a refraction pair (wo outside-side per etap), oriented to +z; false when
// the pair cannot be a refraction through a front-facing microfacet.
inline bool refraction_half_vector(Vec3 wo, Vec3 wi, float etap, Vec3& wm) {
    wm = wi * etap + wo;
    if (wi.z == 0 || wo.z == 0 || dot(wm, wm) == 0) return false;
    wm = normalize(wm);
    if (wm.z < 0) wm = -wm;
    return dot(wm, wi) * wi.z > 0 && dot(wm, wo) * wo.z > 0;
}

// GGX transmission without the (1 - F) factor, radiance or importance; etap as above.
inline float ggx_transmission(const Ggx& g, Vec3 wo, Vec3 wi, Vec3 wm, float etap, Transport mode) {
    const float a = dot(wi, wm) + dot(wo, wm) / etap;
    const float denom = a * a * wi.z * wo.z;
    float f = g.d(wm) * g.g2(wo, wi) * std::abs(dot(wi, wm) * dot(wo, wm) / denom);
    if (mode == Transport::Radiance) f /= etap * etap;
    return f;
}
inline float ggx_transmission_pdf(const Ggx& g, Vec3 wo, Vec3 wi, Vec3 wm, float etap) {
    const float a = dot(wi, wm) + dot(wo, wm) / etap;
    return g.d_visible(wo, wm) * std::abs(dot(wi, wm)) / (a * a);
}

// Metallic-roughness: the probabilities of its three lobes (specular reflection, diffuse,
// transmission) at wo (wo.z > 0 in the frame it is evaluated in), from their albedos' rough sizes.
struct LobeChoice { float spec, diffuse, trans; };

inline float dielectric_scale(const Bsdf& b) { return std::clamp(b.specular * average(b.specular_color), 0.0f, 1.0f); }

inline Vec3 mr_specular_fresnel(const Bsdf& b, float cos_h, float eta) {
    const Vec3 metal = fresnel_schlick(b.base, cos_h);
    const Vec3 diel = vmin(b.specular_color * (b.specular * fresnel_dielectric(cos_h, eta)), Vec3(1));
    return metal * b.metallic + diel * (1 - b.metallic);
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
            if (!two_sided(b)) inv.ior = 1 / b.ior;
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
        if (wi.z > 0) {
            const float lobe = ggx_reflection(g, wo, wi, wm);
            Vec3 f = lobe == 0 ? Vec3(0) : mr_specular_fresnel(b, dot(wo, wm), b.ior) * lobe;
            const float s = dielectric_scale(b);
            const float kd = (1 - b.metallic) * (1 - b.transmission) * (1 - s * fresnel_dielectric(wo.z, b.ior)) *
                             (1 - s * fresnel_dielectric(wi.z, b.ior));
            return f + b.base * (kd / kPi);
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

inline float pdf(const Bsdf& b, Vec3 wo, Vec3 wi) {
    if (wo.z == 0 || wi.z == 0) return 0;
    if (wo.z < 0 && b.kind != Kind::RoughDielectric) {
        Bsdf inv = b;
        if (!two_sided(b)) inv.ior = 1 / b.ior;
        wo.z = -wo.z;
        wi.z = -wi.z;
        return pdf(inv, wo, wi);
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
        const LobeChoice p = mr_lobes(b, wo, b.ior);
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
        s.pdf = pdf(b, wo, w);
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
        const LobeChoice p = mr_lobes(b, o, eta);
        if (p.spec + p.diffuse + p.trans <= 0) return s;
        if (uc < p.spec) {
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
