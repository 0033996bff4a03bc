#pragma once
// The BSDFs every test in this folder runs through: each kind at several roughnesses, with the
// incident angles (from the normal to grazing) and sides it is tested at.
#include <cmath>
#include <string>
#include <vector>

#include "core/bsdf/bsdf.h"
#include "foundation/constants.h"

namespace sl::test {

struct BsdfCase {
    std::string name;
    bsdf::Bsdf b;
};

inline std::vector<BsdfCase> bsdf_cases() {
    using bsdf::Kind;
    std::vector<BsdfCase> out;
    bsdf::Bsdf lam;
    lam.base = Vec3(0.5f, 0.6f, 0.7f);
    out.push_back({"lambert", lam});
    for (float r : {0.3f, 0.6f, 1.0f}) {
        const std::string rs = std::to_string(r).substr(0, 3);
        bsdf::Bsdf c;
        c.kind = Kind::Conductor;
        c.alpha = bsdf::alpha_of_roughness(r);
        c.base = Vec3(0.95f, 0.64f, 0.54f);  // copper's F0
        out.push_back({"conductor_schlick_r" + rs, c});
        c.complex_ior = true;
        c.eta = Vec3(0.2f, 0.92f, 1.1f);  // gold, roughly
        c.k = Vec3(3.9f, 2.45f, 2.14f);
        out.push_back({"conductor_complex_r" + rs, c});
        bsdf::Bsdf d;
        d.kind = Kind::RoughDielectric;
        d.alpha = c.alpha;
        d.ior = 1.5f;
        out.push_back({"rough_dielectric_r" + rs, d});
        bsdf::Bsdf m;
        m.kind = Kind::MetallicRoughness;
        m.alpha = c.alpha;
        m.base = Vec3(0.8f, 0.3f, 0.2f);
        out.push_back({"plastic_r" + rs, m});
        m.blender3_base = true;  // "principled": "blender3": the base uncapped
        out.push_back({"plastic_blender3_r" + rs, m});
        if (r < 0.5f) {  // the halves camera paths take apart where the coat is smooth
            bsdf::Bsdf coat = m, base = m;
            coat.no_diffuse = true;
            base.no_specular = true;
            out.push_back({"plastic_blender3_coat_alone_r" + rs, coat});
            out.push_back({"plastic_blender3_base_alone_r" + rs, base});
        }
        m.blender3_base = false;
        m.metallic = 0.5f;
        out.push_back({"half_metal_r" + rs, m});
        m.metallic = 0;
        m.transmission = 0.7f;
        m.base = Vec3(0.9f, 0.95f, 1.0f);
        out.push_back({"transmissive_r" + rs, m});
    }
    return out;
}

// Incident directions: 0, 30, 60, 80 and 89 degrees from the normal; for the kinds with an
// inside the same from below, for the two-sided ones (a mirror image) 60 degrees from below.
inline std::vector<Vec3> incident_directions(const bsdf::Bsdf& b) {
    std::vector<Vec3> out;
    for (float deg : {0.0f, 30.0f, 60.0f, 80.0f, 89.0f}) {
        const float t = deg * kPi / 180, phi = 0.7f;
        out.push_back(Vec3(std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi), std::cos(t)));
    }
    const size_t n = out.size();
    for (size_t i = 0; i < n; ++i)
        if (!bsdf::two_sided(b) || i == 2) out.push_back(Vec3(out[i].x, out[i].y, -out[i].z));
    return out;
}

}  // namespace sl::test
