// The diffuse base of glTF's metallic-roughness material (core/bsdf/bsdf.h, mr_diffuse): added
// undimmed under the specular layer, with Burley's shape, as Blender's Principled BSDF (Cycles
// 3.4, v1) adds it, capped by the energy-conserving share the layer leaves. Checked: the layer's
// hemispherical average against the known value and against the Stokes relation from inside; the
// base against Burley's 2012 formula where the cap does not bite (what makes Blender's default
// scenes match Cycles); the cap itself at grazing; and white furnaces (albedo <= 1). The
// "blender3" choice (blender3_base) drops the cap: its albedo is Cycles 3.4's sum, gain included.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "core/bsdf/bsdf.h"
#include "foundation/constants.h"
#include "tests/bsdf/sphere_quadrature.h"

namespace sl::test {
namespace {

using bsdf::Kind;

float deg(float d) { return d * kPi / 180; }
Vec3 at_angle(float degrees, float phi = 0) {
    return Vec3(std::sin(deg(degrees)) * std::cos(phi), std::sin(deg(degrees)) * std::sin(phi), std::cos(deg(degrees)));
}

// What Blender 3.4's exporter writes for the default Principled BSDF (specular 0.5: no
// KHR_materials_specular, so glTF's ior 1.5 and F0 = 4 %), roughness 0.5.
bsdf::Bsdf blender_default(Vec3 base) {
    bsdf::Bsdf b;
    b.kind = Kind::MetallicRoughness;
    b.base = base;
    b.alpha = bsdf::alpha_of_roughness(0.5f);
    b.ior = 1.5f;
    return bsdf::cache_layer_averages(b);
}

// Burley's diffuse as his 2012 notes write it: (1 + (F_D90 - 1)(1 - cos_i)^5)(1 + (F_D90 - 1)
// (1 - cos_o)^5), F_D90 = 0.5 + 2 roughness cos^2(half angle) (Cycles factors it differently).
float burley_2012(Vec3 wo, Vec3 wi, float roughness) {
    const Vec3 h = normalize(wo + wi);
    const float fd90 = 0.5f + 2 * roughness * dot(wi, h) * dot(wi, h);
    return (1 + (fd90 - 1) * std::pow(1 - wi.z, 5.0f)) * (1 + (fd90 - 1) * std::pow(1 - wo.z, 5.0f));
}

TEST(MetallicRoughnessBase, LayerAverageMatchesKnownValuesAndStokes) {
    bsdf::Bsdf b;
    b.kind = Kind::MetallicRoughness;
    b.ior = 1.5f;
    b.alpha = bsdf::kMinAlpha;  // a smooth layer: its share is the Fresnel curve itself
    b = bsdf::cache_layer_averages(b);
    // The hemispherical (cosine-weighted) reflectance of a smooth n = 1.5 interface: 0.0918.
    EXPECT_NEAR(b.layer_avg_out, 0.0918f, 3e-4f);
    // From inside, light below the critical angle is reflected whole; what leaves obeys
    // 1 - r_in = (1 - r_out) / n^2 (reciprocity of the interface's transmission).
    EXPECT_NEAR(1 - b.layer_avg_in, (1 - b.layer_avg_out) / (1.5f * 1.5f), 3e-4f);
    // The cached values are those computed on the fly.
    bsdf::Bsdf raw = b;
    raw.layer_avg_out = raw.layer_avg_in = -1;
    const Vec3 wo = at_angle(40), wi = at_angle(70, 2.0f);
    const Vec3 a = bsdf::eval(b, wo, wi), c = bsdf::eval(raw, wo, wi);
    EXPECT_FLOAT_EQ(a.x, c.x);
}

// f(base) - f(black base) is the diffuse part alone: the base colour times Burley's shape / pi,
// undimmed by the layer (Cycles 3.4's Principled v1), while the two directions leave the layer
// enough light.
TEST(MetallicRoughnessBase, BaseIsUndimmedAsInCyclesAwayFromGrazing) {
    const bsdf::Bsdf grey = blender_default(Vec3(0.6f)), black = blender_default(Vec3(0));
    for (float o : {0.0f, 30.0f, 60.0f, 72.0f})
        for (float i : {0.0f, 45.0f, 60.0f, 80.0f}) {
            SCOPED_TRACE("wo " + std::to_string(o) + " wi " + std::to_string(i));
            const Vec3 wo = at_angle(o), wi = at_angle(i, 2.5f);
            const float diffuse = bsdf::eval(grey, wo, wi).y - bsdf::eval(black, wo, wi).y;
            EXPECT_NEAR(diffuse, 0.6f * burley_2012(wo, wi, 0.5f) / kPi, 1e-5f);
        }
    // Retro-reflection 5 degrees from grazing, where Burley's shape exceeds 1.7: the cap bites,
    // (1 - S(o))(1 - S(i)) / (1 - average S), S the smooth Fresnel read no further than the
    // cosine roughness^1.5 / 2 = 0.177.
    const Vec3 w = at_angle(85);
    const float diffuse = bsdf::eval(grey, w, w).y - bsdf::eval(black, w, w).y;
    const float s = bsdf::fresnel_dielectric(0.5f * std::pow(0.5f, 1.5f), 1.5f);
    EXPECT_NEAR(diffuse, (1 - s) * (1 - s) / (1 - grey.layer_avg_out) / kPi, 1e-6f);
    EXPECT_LT(diffuse, 0.6f * burley_2012(w, w, 0.5f) / kPi);
}

// Without a layer (specular 0) the base is the Lambertian glTF defines: base / pi exactly.
TEST(MetallicRoughnessBase, WithoutALayerTheBaseIsLambertian) {
    bsdf::Bsdf b = blender_default(Vec3(0.7f, 0.5f, 0.3f));
    b.specular = 0;
    b = bsdf::cache_layer_averages(b);
    for (float o : {0.0f, 45.0f, 80.0f, 89.0f})
        for (float i : {0.0f, 60.0f, 85.0f}) {
            const Vec3 f = bsdf::eval(b, at_angle(o), at_angle(i, 1.0f));
            EXPECT_FLOAT_EQ(f.x, 0.7f / kPi);
            EXPECT_FLOAT_EQ(f.z, 0.3f / kPi);
        }
}

// The directional albedo by sampling (the mean of the sample weights).
double albedo(const bsdf::Bsdf& b, Vec3 wo, int n, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    double sum = 0;
    for (int k = 0; k < n; ++k) {
        const bsdf::Sample s = bsdf::sample(b, wo, u(rng), u(rng), u(rng), bsdf::Transport::Importance);
        if (s.valid) sum += s.weight.y;
    }
    return sum / n;
}

// White furnace on Blender's default layer: a white base returns no more than came in at any
// angle or roughness (the cap's bound E_layer(o) + 1 - F(o) <= 1), and loses little; a grey
// base returns the layer's own albedo plus its colour times Burley's albedo (Cycles' sum, the
// base undimmed), which is 0.6 within 4 % at roughness <= 0.5.
TEST(MetallicRoughnessBase, WhiteFurnaceOnBlendersDefaultLayer) {
    for (float r : {0.1f, 0.3f, 0.5f, 0.8f, 1.0f}) {
        bsdf::Bsdf white = blender_default(Vec3(1)), grey = blender_default(Vec3(0.6f)),
                   black = blender_default(Vec3(0));
        white.alpha = grey.alpha = black.alpha = bsdf::alpha_of_roughness(r);
        for (float a : {0.0f, 30.0f, 60.0f, 80.0f, 89.0f}) {
            SCOPED_TRACE("roughness " + std::to_string(r) + " at " + std::to_string(a) + " deg");
            const double w = albedo(white, at_angle(a), 200000, 31);
            EXPECT_LE(w, 1.0 + 3e-3);  // 200k draws: the mean is known to ~1e-3
            if (a <= 60) {
                EXPECT_GT(w, 0.92);  // measured down to 0.934 (roughness 1, 60 deg: Burley and GGX's loss)
                const double layer = albedo(black, at_angle(a), 200000, 32);
                const double base = albedo(grey, at_angle(a), 200000, 33) - layer;
                if (r <= 0.5f) EXPECT_NEAR(base, 0.6, 0.6 * 0.04);  // measured 0.581 at roughness 0.1, 60 deg
            }
        }
    }
}

// One channel's directional albedo by sampling (the mean of the sample weights).
double albedo_channel(const bsdf::Bsdf& b, Vec3 wo, int channel, int n, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    double sum = 0;
    for (int k = 0; k < n; ++k) {
        const bsdf::Sample s = bsdf::sample(b, wo, u(rng), u(rng), u(rng), bsdf::Transport::Importance);
        if (s.valid) sum += s.weight[channel];
    }
    return sum / n;
}

// "principled": "blender3": the base is base x Burley's shape / pi at every pair of directions,
// grazing retro-reflection included, where the default caps it.
TEST(MetallicRoughnessBase, Blender3BaseIsBurleyUncappedEverywhere) {
    bsdf::Bsdf grey = blender_default(Vec3(0.6f)), black = blender_default(Vec3(0));
    grey.blender3_base = black.blender3_base = true;
    for (float o : {0.0f, 30.0f, 60.0f, 80.0f, 85.0f, 89.0f})
        for (float i : {0.0f, 45.0f, 80.0f, 85.0f, 89.0f}) {
            SCOPED_TRACE("wo " + std::to_string(o) + " wi " + std::to_string(i));
            const Vec3 wo = at_angle(o), wi = at_angle(i, o == i ? 0.0f : 2.5f);
            const float diffuse = bsdf::eval(grey, wo, wi).y - bsdf::eval(black, wo, wi).y;
            EXPECT_NEAR(diffuse, 0.6f * burley_2012(wo, wi, 0.5f) / kPi, 2e-5f * (1 + diffuse));
        }
    // 85 degrees both ways, where the default caps it (MetallicRoughnessBase.BaseIsUndimmed...):
    const Vec3 w = at_angle(85);
    bsdf::Bsdf capped = blender_default(Vec3(0.6f)), capped_black = blender_default(Vec3(0));
    const float uncapped = bsdf::eval(grey, w, w).y - bsdf::eval(black, w, w).y;
    EXPECT_GT(uncapped, 1.2f * (bsdf::eval(capped, w, w).y - bsdf::eval(capped_black, w, w).y));
    // Without a layer it stays glTF's Lambertian surface, as the default's.
    grey.specular = 0;
    grey = bsdf::cache_layer_averages(grey);
    EXPECT_FLOAT_EQ(bsdf::eval(grey, at_angle(80), at_angle(85, 1.0f)).x, 0.6f / kPi);
}

// The red plastic cube of bench/blender/glossy_scene.py (base 0.8, 0.1, 0.1, roughness 0.2, F0
// 4 %) seen 80 degrees from its normal. With "blender3" its red albedo is what Cycles 3.4's
// Principled v1 returns: the layer's own albedo (sampled from the black-base material) plus
// 0.8 x Burley's albedo, integrated here by quadrature of Burley's 2012 formula; that is more
// than 1 (measured 1.055: the gain docs/materials.md states), where the default stays <= 1.
TEST(MetallicRoughnessBase, Blender3AlbedoIsCyclesSumWithItsGain) {
    const float roughness = 0.2f;
    auto plastic = [&](Vec3 base, bool blender3) {
        bsdf::Bsdf b = blender_default(base);
        b.alpha = bsdf::alpha_of_roughness(roughness);
        b.blender3_base = blender3;
        return bsdf::cache_layer_averages(b);
    };
    for (float a : {0.0f, 60.0f, 80.0f}) {
        SCOPED_TRACE("at " + std::to_string(a) + " deg");
        const Vec3 wo = at_angle(a);
        const double layer = albedo_channel(plastic(Vec3(0), true), wo, 0, 400000, 41);
        const std::array<double, 3> burley = integrate_sphere(SphereGrid{}, [&](Vec3 wi) {
            return wi.z > 0 ? Vec3(burley_2012(wo, wi, roughness) * wi.z / kPi) : Vec3(0);
        });
        const double expected = layer + 0.8 * burley[0];
        const double red = albedo_channel(plastic(Vec3(0.8f, 0.1f, 0.1f), true), wo, 0, 400000, 42);
        std::printf("red plastic, roughness 0.2, %2.0f deg: layer %.4f + 0.8 x Burley %.4f = %.4f; blender3 "
                    "sampled %.4f\n", a, layer, burley[0], expected, red);
        EXPECT_NEAR(red, expected, 0.005 * expected);  // 4e5 draws: ~1e-3
        if (a == 80) {
            EXPECT_GT(red, 1.04);  // Cycles' gain (1.055 measured, docs/materials.md)
            const double capped = albedo_channel(plastic(Vec3(0.8f, 0.1f, 0.1f), false), wo, 0, 400000, 43);
            EXPECT_LE(capped, 1.0 + 3e-3);  // the default: no gain
            std::printf("  energy_conserving %.4f\n", capped);
        }
    }
}

}  // namespace
}  // namespace sl::test
