// GGX surfaces in the estimator (docs/materials.md, "In the renderer"): direct light weighed
// by f(wo, wi)|cos| on both kinds of GGX vertex (a visible point that gathers, and a glossy
// vertex camera paths follow), and the photon gather weighing each photon by f(wo, wi_photon).
// The expected values come from the GGX formulas written out here again (Walter et al. 2007,
// Heitz 2014), not from core/bsdf/.
#include <gtest/gtest.h>

#include <cmath>

#include "core/import/mesh_data.h"
#include "core/material_table.h"
#include "light_paths_helpers.h"

namespace sl {
namespace {

// --- the GGX microfacet BRDF, written independently of core/bsdf/ ----------------------------

double ggx_d(double alpha, double cos_h) {
    const double a2 = alpha * alpha, c2 = cos_h * cos_h;
    const double den = c2 * (a2 - 1) + 1;
    return a2 / (M_PI * den * den);
}
double smith_lambda(double alpha, double cos_t) {
    const double tan2 = (1 - cos_t * cos_t) / (cos_t * cos_t);
    return (-1 + std::sqrt(1 + alpha * alpha * tan2)) / 2;
}
double schlick(double f0, double c) { return f0 + (1 - f0) * std::pow(1 - c, 5); }
// Unpolarised Fresnel reflectance from outside a dielectric of index n.
double fresnel(double cos_i, double n) {
    const double sin_t2 = (1 - cos_i * cos_i) / (n * n);
    if (sin_t2 >= 1) return 1;
    const double cos_t = std::sqrt(1 - sin_t2);
    const double rs = (cos_i - n * cos_t) / (cos_i + n * cos_t), rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    return (rs * rs + rp * rp) / 2;
}
// The specular lobe without Fresnel, D G2 / (4 cos_o cos_i), for unit wo, wi about normal n;
// cos_h_o: wo . h (Fresnel's angle).
double ggx_lobe(double alpha, Vec3 n, Vec3 wo, Vec3 wi, double& cos_h_o) {
    const double co = dot(n, wo), ci = dot(n, wi);
    if (co <= 0 || ci <= 0) return 0;
    const Vec3 h = normalize(wo + wi);
    cos_h_o = dot(wo, h);
    const double g2 = 1 / (1 + smith_lambda(alpha, co) + smith_lambda(alpha, ci));
    return ggx_d(alpha, dot(n, h)) * g2 / (4 * co * ci);
}

// A conductor (Schlick, F0) plane.
double conductor_f(double f0, double roughness, Vec3 n, Vec3 wo, Vec3 wi) {
    double c = 0;
    const double lobe = ggx_lobe(roughness * roughness, n, wo, wi, c);
    return lobe * schlick(f0, c);
}
// glTF's metallic-roughness with metallic 0, as Blender's Principled v1 draws it: the dielectric
// GGX layer added over Burley's diffuse base (its 2012 form), the base capped by the share the
// layer leaves, (1 - S(o))(1 - S(i)) / (1 - average S), S = F read no closer to grazing than
// roughness^1.5 / 2 (docs/materials.md); the average here by 20000 midpoints.
double plastic_f(double base, double roughness, double ior, Vec3 n, Vec3 wo, Vec3 wi) {
    double c = 0;
    const double lobe = ggx_lobe(roughness * roughness, n, wo, wi, c);
    const double spec = lobe > 0 ? lobe * fresnel(c, ior) : 0;
    const double co = dot(n, wo), ci = dot(n, wi);
    const Vec3 h = normalize(wo + wi);
    const double fd90 = 0.5 + 2 * roughness * dot(wi, h) * dot(wi, h);
    const double burley = (1 + (fd90 - 1) * std::pow(1 - ci, 5)) * (1 + (fd90 - 1) * std::pow(1 - co, 5));
    const double mu0 = 0.5 * std::pow(roughness, 1.5);
    auto share = [&](double mu) { return fresnel(std::max(mu, mu0), ior); };
    double avg = 0;
    const int m = 20000;
    for (int k = 0; k < m; ++k) {
        const double mu = (k + 0.5) / m;
        avg += 2 * mu * share(mu) / m;
    }
    const double cap = (1 - share(co)) * (1 - share(ci)) / (1 - avg);
    return spec + std::min(base * burley, cap) / M_PI;
}

// --- scenes -----------------------------------------------------------------------------------

constexpr float kPower = 40;
const Vec3 kCam{-0.6f, 0, 1.0f}, kLight{0.5f, 0.1f, 0.8f};

// A plane z = 0 of material m, a point light and a camera on opposite sides of the reflection.
SceneDesc plane_scene(MaterialDesc m) {
    SceneDesc s = lp::empty_scene(kCam, {0.05f, 0, 0}, {0, 0, 1}, 30, 32);
    m.name = "plane";
    s.materials.push_back(m);
    lp::add_quad(s, {-3, -3, 0}, {6, 0, 0}, {0, 6, 0}, 0);
    lp::add_point_light(s, kLight, kPower);
    s.time = {0, 12, 12, 24};
    s.emission.mode = EmissionMode::Constant;
    s.render.max_depth = 4;
    s.render.passes = 4;
    s.render.photons_per_pass = 2000;
    return s;
}

// Rendered against expected radiance, summed over every pixel, and the worst pixel's ratio.
struct Compared {
    double ratio = 0, worst = 0;
    int pixels = 0;
};

template <class F>
Compared compare_direct(const SceneDesc& s, F&& f) {
    const lp::Rendered r = lp::render_all(s);
    const PinholeCamera cam(s.camera);
    const double intensity = kPower / (4 * M_PI);
    double got = 0, want = 0;
    Compared c;
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            const Vec3 p = lp::on_plane(cam, x + 0.5f, y + 0.5f, {0, 0, 1}, 0);
            const Vec3 wo = normalize(kCam - p), to_l = kLight - p, wi = normalize(to_l);
            const double l = f(wo, wi) * intensity * wi.z / dot(to_l, to_l);
            if (!(l > 1e-3)) continue;  // the pixel's jitter makes relative errors large where dark
            got += r.steady_at(x, y);
            want += l;
            c.worst = std::max(c.worst, std::abs(r.steady_at(x, y) / l - 1));
            ++c.pixels;
        }
    c.ratio = got / want;
    return c;
}

MaterialDesc conductor(float f0, float roughness) {
    MaterialDesc m;
    m.type = MaterialType::Conductor;
    m.reflectance = Vec3(f0);
    m.roughness = roughness;
    return m;
}

// Direct light on a rough metal, both where camera paths follow the GGX lobe (roughness 0.3: the
// light is sampled at the glossy vertex) and where they end on it (0.7: a visible point).
TEST(Glossy, PointLightOnRoughMetalIsDFGOverFourCosCos) {
    for (float roughness : {0.3f, 0.7f}) {
        const MaterialDesc m = conductor(0.9f, roughness);
        EXPECT_EQ(glossy_use(m), roughness < kFollowBelowRoughness ? GlossyUse::Follow : GlossyUse::Gather);
        const Compared c = compare_direct(plane_scene(m), [&](Vec3 wo, Vec3 wi) {
            return conductor_f(0.9, roughness, {0, 0, 1}, wo, wi);
        });
        EXPECT_GT(c.pixels, 300);
        EXPECT_NEAR(c.ratio, 1.0, 0.01) << "roughness " << roughness;
        std::printf("[glossy, point light on rough metal, roughness %.1f] rendered / GGX formula %.4f over %d "
                    "pixels, worst pixel %.3f off\n",
                    roughness, c.ratio, c.pixels, c.worst);
    }
}

TEST(Glossy, PointLightOnPlasticIsSpecularLayerPlusCappedBurleyBase) {
    MaterialDesc m;
    m.type = MaterialType::MetallicRoughness;
    m.albedo = Vec3(0.5f);
    m.metallic = 0;
    m.roughness = 0.4f;
    m.ior = 1.5f;
    EXPECT_EQ(glossy_use(m), GlossyUse::Gather);
    const Compared c = compare_direct(plane_scene(m), [&](Vec3 wo, Vec3 wi) {
        return plastic_f(0.5, 0.4, 1.5, {0, 0, 1}, wo, wi);
    });
    EXPECT_GT(c.pixels, 300);
    EXPECT_NEAR(c.ratio, 1.0, 0.01);
    std::printf("[glossy, point light on plastic] rendered / formula %.4f over %d pixels, worst pixel %.3f off\n",
                c.ratio, c.pixels, c.worst);
}

// The photon gather at a GGX visible point: a laser (its light comes by photons only) lights a
// spot on a rough metal plane seen at an angle. Radiance integrated over the spot's area,
// sum over pixels of L x the pixel's footprint on the plane, is f(wo, wi) x the laser's power,
// whatever the gather radius; with the Lambertian weight it would be (albedo / pi) P.
TEST(Glossy, LaserSpotOnRoughMetalHoldsFTimesPower) {
    const float roughness = 0.5f;
    SceneDesc s = lp::empty_scene({-0.8f, 0, 0.9f}, {0, 0, 0}, {0, 0, 1}, 12, 48);
    MaterialDesc m = conductor(0.9f, roughness);
    m.name = "metal";
    s.materials.push_back(m);
    lp::add_quad(s, {-3, -3, 0}, {6, 0, 0}, {0, 6, 0}, 0);
    const Vec3 from{0.6f, 0, 0.6f};
    lp::add_laser(s, from, -from, 0.02f, kPower);
    s.time = {0, 12, 12, 24};
    s.emission.mode = EmissionMode::Constant;
    s.render.max_depth = 2;
    s.render.passes = 16;
    s.render.photons_per_pass = 20000;
    s.render.radius = 0.01f;
    const lp::Rendered r = lp::render_all(s);
    const PinholeCamera cam(s.camera);
    double sum = 0;
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            const Vec3 a = lp::on_plane(cam, x, y, {0, 0, 1}, 0), b = lp::on_plane(cam, x + 1, y, {0, 0, 1}, 0),
                       c = lp::on_plane(cam, x, y + 1, {0, 0, 1}, 0);
            sum += r.steady_at(x, y) * length(cross(b - a, c - a));
        }
    const Vec3 wo = normalize(s.camera.position), wi = normalize(from);
    const double want = conductor_f(0.9, roughness, {0, 0, 1}, wo, wi) * kPower;
    EXPECT_NEAR(sum / want, 1.0, 0.03);
    EXPECT_GT(want / kPower, 1.5 * 0.9 / M_PI);  // the test tells f from the Lambertian weight
    std::printf("[glossy, laser spot on rough metal] integrated radiance / (f P) = %.4f (f = %.4f; Lambertian "
                "albedo/pi would be %.4f)\n",
                sum / want, want / kPower, 0.9 / M_PI);
}

// --- a furnace: a closed box whose walls emit and reflect ---------------------------------------

// A white conductor (F = 1) emits Le from every wall of the cube [-1, 1]^3. With max_depth 1 a
// camera at the centre sees Le (1 + E(mu_o)), E the GGX's directional albedo; with max_depth 2
// it adds the light reflected once on the way, Le E2(wo) = Le int f(wo, wi) E(mu_B(wi)) cos dwi,
// mu_B the cosine at the wall the direction wi meets. The first comes from direct light at the
// vertex (a visible point at roughness 0.7, a followed vertex at 0.4), the second from photons
// (roughness 0.7) or, at roughness 0.4, from the next followed vertex: its light samples and
// the followed direction's hits on the walls, weighed by multiple importance sampling (light
// samples alone, whose weight f cos cos / d^2 is heavy-tailed, reached 0.877 of E2 at 32
// passes). E and E2 are integrated here from the GGX formula above.
struct Albedo {
    double alpha;
    std::vector<double> table;  // E at mu = (i + 0.5) / n
    static constexpr int kN = 64;
    // E(mu) by the midpoint rule in (theta_i, phi).
    static double integrate(double alpha, Vec3 wo, int n) {
        double sum = 0;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < 2 * n; ++j) {
                const double th = M_PI / 2 * (i + 0.5) / n, c = std::cos(th), sn = std::sin(th), phi = M_PI * (j + 0.5) / n;
                const Vec3 wi(float(sn * std::cos(phi)), float(sn * std::sin(phi)), float(c));
                double h = 0;
                sum += ggx_lobe(alpha, {0, 0, 1}, wo, wi, h) * c * sn;
            }
        return sum * (M_PI / 2 / n) * (M_PI / n);
    }
    explicit Albedo(double a) : alpha(a) {
        for (int i = 0; i < kN; ++i) {
            const double mu = (i + 0.5) / kN;
            table.push_back(integrate(alpha, Vec3(float(std::sqrt(1 - mu * mu)), 0, float(mu)), 400));
        }
    }
    double at(double mu) const {
        const double x = std::clamp(mu * kN - 0.5, 0.0, kN - 1.0);
        const int i = std::min(int(x), kN - 2);
        return table[i] + (x - i) * (table[i + 1] - table[i]);
    }
};

// E2 at the point p of the wall z = -1 (normal +z), seen from direction wo.
double once_reflected(const Albedo& e, Vec3 p, Vec3 wo, int n) {
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < 2 * n; ++j) {
            const double th = M_PI / 2 * (i + 0.5) / n, c = std::cos(th), sn = std::sin(th), phi = M_PI * (j + 0.5) / n;
            const Vec3 wi(float(sn * std::cos(phi)), float(sn * std::sin(phi)), float(c));
            double h = 0;
            const double f = ggx_lobe(e.alpha, {0, 0, 1}, wo, wi, h);
            if (f == 0) continue;
            double t = 1e30, mu = 0;  // the wall the ray p + t wi leaves the cube by
            for (int k = 0; k < 3; ++k) {
                const double w = k == 0 ? wi.x : k == 1 ? wi.y : wi.z, q = k == 0 ? p.x : k == 1 ? p.y : p.z;
                if (w == 0) continue;
                const double tk = ((w > 0 ? 1 : -1) - q) / w;
                if (tk > 1e-9 && tk < t) t = tk, mu = std::abs(w);
            }
            sum += f * e.at(mu) * c * sn;
        }
    return sum * (M_PI / 2 / n) * (M_PI / n);
}

SceneDesc furnace(float roughness, int max_depth) {
    SceneDesc s = lp::empty_scene({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 30, 16);
    MaterialDesc m = conductor(1.0f, roughness);
    m.name = "white_metal";
    m.emission = Vec3(1);
    m.double_sided = true;
    s.materials.push_back(m);
    auto mesh = std::make_shared<MeshData>();
    for (int i = 0; i < 8; ++i) mesh->positions.push_back(Vec3(i & 1 ? 1.f : -1.f, i & 2 ? 1.f : -1.f, i & 4 ? 1.f : -1.f));
    mesh->indices = {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                     2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3};
    mesh->tri_material.assign(12, 0);
    ShapeDesc shape;
    shape.type = ShapeType::Mesh;
    shape.material = 0;
    shape.mesh = mesh;
    s.shapes.push_back(shape);
    s.time = {0, 40, 4, 24};
    s.emission.mode = EmissionMode::Constant;
    s.render.max_depth = max_depth;
    s.render.passes = 32;
    s.render.photons_per_pass = 100000;
    s.render.radius = 0.03f;
    return s;
}

TEST(Glossy, FurnaceOfEmittingWhiteMetalMatchesItsAlbedo) {
    for (float roughness : {0.7f, 0.4f}) {
        const Albedo e(roughness * roughness);
        double got1 = 0, got2 = 0, want1 = 0, want2 = 0;
        const bool photons = glossy_use(furnace(roughness, 1).materials[0]) == GlossyUse::Gather;
        const lp::Rendered r1 = lp::render_all(furnace(roughness, 1)), r2 = lp::render_all(furnace(roughness, 2));
        const SceneDesc s = furnace(roughness, 1);
        const PinholeCamera cam(s.camera);
        for (int y = 0; y < r1.height; ++y)
            for (int x = 0; x < r1.width; ++x) {
                const Vec3 p = lp::on_plane(cam, x + 0.5f, y + 0.5f, {0, 0, 1}, -1), wo = normalize(-p);
                want1 += 1 + e.at(wo.z);
                want2 += once_reflected(e, p, wo, 150);
                got1 += r1.steady_at(x, y);
                got2 += r2.steady_at(x, y) - r1.steady_at(x, y);
            }
        EXPECT_NEAR(got1 / want1, 1.0, 0.01) << "roughness " << roughness;
        std::printf("[glossy furnace, white metal, roughness %.1f] direct: rendered / Le (1 + E) = %.4f (E at normal "
                    "incidence %.4f)",
                    roughness, got1 / want1, e.at(1));
        EXPECT_NEAR(got2 / want2, 1.0, 0.04) << "roughness " << roughness;
        std::printf("; once reflected, by %s: rendered / Le E2 = %.4f\n", photons ? "photons" : "MIS", got2 / want2);
    }
}

}  // namespace
}  // namespace sl
