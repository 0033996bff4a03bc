// A parsed material's BSDF (core/bsdf/material_bsdf.h) and its stand-in among the three
// surfaces the estimator draws today (core/material_stand_in.h): the rules the docs' table
// states, and which of them warn.
#include <gtest/gtest.h>

#include "core/bsdf/material_bsdf.h"
#include "core/material_stand_in.h"

namespace sl::test {
namespace {

MaterialDesc material(MaterialType t, float roughness) {
    MaterialDesc d;
    d.type = t;
    d.roughness = roughness;
    return d;
}

TEST(MaterialBsdf, ParametersReachTheBsdf) {
    MaterialDesc c = material(MaterialType::Conductor, 0.3f);
    c.complex_ior = true;
    c.eta = Vec3(0.2f, 0.9f, 1.1f);
    c.k = Vec3(3.9f, 2.4f, 2.1f);
    const bsdf::Bsdf b = *bsdf_of(c);
    EXPECT_EQ(b.kind, bsdf::Kind::Conductor);
    EXPECT_FLOAT_EQ(b.alpha, 0.09f);  // roughness^2
    // At normal incidence on a smooth-ish lobe the reflected colour is the conductor's F0.
    const Vec3 f0 = conductor_f0(c);
    EXPECT_NEAR(f0.x, bsdf::fresnel_complex(1, 0.2f, 3.9f), 1e-6f);
    MaterialDesc p = material(MaterialType::MetallicRoughness, 0.5f);
    p.metallic = 0.3f;
    p.transmission = 0.2f;
    p.specular = 0.7f;
    const bsdf::Bsdf q = *bsdf_of(p);
    EXPECT_EQ(q.kind, bsdf::Kind::MetallicRoughness);
    EXPECT_FLOAT_EQ(q.metallic, 0.3f);
    EXPECT_FLOAT_EQ(q.transmission, 0.2f);
    EXPECT_FLOAT_EQ(q.specular, 0.7f);
    EXPECT_FALSE(bsdf_of(material(MaterialType::Mirror, 0)).has_value());  // specular events
    EXPECT_EQ(bsdf_of(material(MaterialType::Diffuse, 0))->kind, bsdf::Kind::Lambert);
}

TEST(MaterialStandIn, RulesAndWarnings) {
    // Conductors: a mirror up to roughness 0.1, else diffuse (warned).
    EXPECT_EQ(stand_in(material(MaterialType::Conductor, 0.05f)).type, MaterialType::Mirror);
    EXPECT_TRUE(approximation_note(material(MaterialType::Conductor, 0.05f)).empty());
    EXPECT_EQ(stand_in(material(MaterialType::Conductor, 0.3f)).type, MaterialType::Diffuse);
    EXPECT_NE(approximation_note(material(MaterialType::Conductor, 0.3f)).find("rough metal"), std::string::npos);
    // Rough glass: smooth glass, warned when rough.
    EXPECT_EQ(stand_in(material(MaterialType::RoughDielectric, 0.5f)).type, MaterialType::Dielectric);
    EXPECT_NE(approximation_note(material(MaterialType::RoughDielectric, 0.5f)).find("drawn smooth"), std::string::npos);
    // Metallic-roughness: Blender's default material and an Emission-only one are not warned.
    MaterialDesc plastic = material(MaterialType::MetallicRoughness, 0.5f);
    EXPECT_EQ(stand_in(plastic).type, MaterialType::Diffuse);
    EXPECT_TRUE(approximation_note(plastic).empty());
    MaterialDesc emission_only = material(MaterialType::MetallicRoughness, 1.0f);
    emission_only.albedo = Vec3(0);
    emission_only.metallic = 1;
    EXPECT_TRUE(approximation_note(emission_only).empty());
    MaterialDesc metal = emission_only;
    metal.albedo = Vec3(0.9f);
    EXPECT_NE(approximation_note(metal).find("rough metal"), std::string::npos);
    metal.roughness = 0.05f;
    EXPECT_EQ(stand_in(metal).type, MaterialType::Mirror);
    EXPECT_FLOAT_EQ(stand_in(metal).reflectance.x, 0.9f);
    MaterialDesc glass = plastic;
    glass.transmission = 1;
    glass.albedo = Vec3(1);
    glass.roughness = 0;
    EXPECT_EQ(stand_in(glass).type, MaterialType::Dielectric);
    EXPECT_TRUE(approximation_note(glass).empty());
    // The three surfaces the estimator draws exactly stand for themselves.
    for (MaterialType t : {MaterialType::Diffuse, MaterialType::Mirror, MaterialType::Dielectric}) {
        EXPECT_EQ(stand_in(material(t, 0.5f)).type, t);
        EXPECT_TRUE(approximation_note(material(t, 0.5f)).empty());
    }
}

}  // namespace
}  // namespace sl::test
