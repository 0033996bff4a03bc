// A parsed material's BSDF (core/bsdf/material_bsdf.h) and how camera paths use it
// (core/material_table.h): the rules the docs' table states.
#include <gtest/gtest.h>

#include "core/bsdf/material_bsdf.h"
#include "core/glossy_path.h"
#include "core/material_table.h"

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
    const Vec3 f0 = bsdf::fresnel_conductor(1, c.eta, c.k);
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

// How camera paths use each GGX material (core/material_table.h; the table in
// docs/scene-format.md): followed when glossy or when it has an inside, else a visible point.
TEST(MaterialGlossyUse, RulesOfTheDocsTable) {
    EXPECT_EQ(glossy_use(material(MaterialType::Conductor, 0.05f)), GlossyUse::Follow);
    EXPECT_EQ(glossy_use(material(MaterialType::Conductor, 0.49f)), GlossyUse::Follow);
    EXPECT_EQ(glossy_use(material(MaterialType::Conductor, 0.5f)), GlossyUse::Gather);
    EXPECT_EQ(glossy_use(material(MaterialType::RoughDielectric, 1.0f)), GlossyUse::Follow);
    MaterialDesc plastic = material(MaterialType::MetallicRoughness, 0.2f);  // a diffuse base: gathers
    EXPECT_EQ(glossy_use(plastic), GlossyUse::Gather);
    MaterialDesc metal = plastic;
    metal.metallic = 1;
    EXPECT_EQ(glossy_use(metal), GlossyUse::Follow);
    metal.roughness = 0.7f;
    EXPECT_EQ(glossy_use(metal), GlossyUse::Gather);
    MaterialDesc glass = plastic;
    glass.transmission = 0.3f;
    EXPECT_EQ(glossy_use(glass), GlossyUse::Follow);
    for (MaterialType t : {MaterialType::Diffuse, MaterialType::Mirror, MaterialType::Dielectric})
        EXPECT_EQ(glossy_use(material(t, 0.5f)), GlossyUse::None);
}

// The table's coat row: a metallic-roughness surface that gathers has its coat followed where
// the coat is smoother than 0.5, the base is not black and it is not a metal or glass.
TEST(MaterialGlossyUse, ASmoothCoatOverADiffuseBaseIsFollowed) {
    bsdf::Bsdf b;
    b.kind = bsdf::Kind::MetallicRoughness;
    b.base = Vec3(0.8f, 0.1f, 0.1f);
    b.alpha = bsdf::alpha_of_roughness(0.2f);
    EXPECT_TRUE(smooth_coat(b));
    b.alpha = bsdf::alpha_of_roughness(0.5f);  // Blender's default Principled: gathered whole
    EXPECT_FALSE(smooth_coat(b));
    b.alpha = bsdf::alpha_of_roughness(0.2f);
    bsdf::Bsdf metal = b, glass = b, black = b, no_coat = b;
    metal.metallic = 1;
    glass.transmission = 1;
    black.base = Vec3(0);
    no_coat.specular = 0;  // a Lambertian surface
    for (const bsdf::Bsdf& x : {metal, glass, black, no_coat}) EXPECT_FALSE(smooth_coat(x));
}

}  // namespace
}  // namespace sl::test
