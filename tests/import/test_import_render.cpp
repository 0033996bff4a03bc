// Imported scenes against what they must equal: the same Cornell box as JSON, OBJ+MTL and glTF;
// an emissive quad mesh against the quad light; a textured plane against the analytic direct
// light per checker square; a tessellated sphere against the analytic sphere.
#include <gtest/gtest.h>

#include <cmath>

#include "core/import/resolve_imports.h"
#include "stages/output/png_io.h"
#include "tests/common/temp_dir.h"
#include "tests/import/model_writers.h"
#include "tests/render/render_helpers.h"
#include "tests/render/scenes_for_tests.h"

namespace sl::test {
namespace {

// The Cornell box of the samples (walls, two boxes), its quad light apart.
ModelMesh cornell_mesh(std::vector<ModelMaterial>& mats) {
    mats = {{"white", Vec3(0.73f)}, {"red", {0.63f, 0.065f, 0.05f}}, {"green", {0.14f, 0.45f, 0.091f}}};
    ModelMesh m;
    m.quad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0);
    m.quad({-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, 0);
    m.quad({-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, 0);
    m.quad({-1, 0, 1}, {0, 0, -2}, {0, 2, 0}, 1);
    m.quad({1, 0, -1}, {0, 0, 2}, {0, 2, 0}, 2);
    m.box({-0.65f, 0, -0.6f}, {-0.05f, 1.2f, -0.05f}, 0);
    m.box({0.1f, 0, 0.05f}, {0.7f, 0.6f, 0.65f}, 0);
    return m;
}

LightDesc cornell_light() {
    LightDesc l;
    l.type = LightType::Quad;
    l.corner = {-0.25f, 1.98f, -0.2f};
    l.edge1 = {0.5f, 0, 0};
    l.edge2 = {0, 0, 0.4f};
    l.radiance = {17, 12, 4};
    return l;
}

SceneDesc cornell_base(uint64_t seed) {
    SceneDesc s;
    s.source = "<cornell>";
    s.camera.position = {0, 1, 3.6f};
    s.camera.look_at = {0, 1, 0};
    s.camera.vfov_deg = 38;
    s.camera.width = s.camera.height = 24;
    s.time = {0, 24, 8, 24};
    s.render.passes = 8;
    s.render.photons_per_pass = 20000;
    s.render.seed = seed;
    return s;
}

// The scene JSON's way: one quad per face, the quad light.
SceneDesc cornell_json(uint64_t seed) {
    SceneDesc s = cornell_base(seed);
    std::vector<ModelMaterial> mats;
    ModelMesh m = cornell_mesh(mats);
    for (const ModelMaterial& mm : mats) {
        MaterialDesc d;
        d.name = mm.name;
        d.albedo = mm.albedo;
        s.materials.push_back(d);
    }
    for (size_t q = 0; q < m.positions.size(); q += 4)
        s.shapes.push_back(quad(m.positions[q], m.positions[q + 1] - m.positions[q], m.positions[q + 3] - m.positions[q],
                                m.tri_material[q / 2]));
    s.lights.push_back(cornell_light());
    return s;
}

SceneDesc with_file(SceneDesc s, ShapeType type, const std::string& file) {
    ShapeDesc sh;
    sh.type = type;
    sh.file = file;
    sh.material = -1;
    s.shapes.push_back(sh);
    return s;
}

// Root-mean-square difference over the steady image and every frame.
double difference(const Rendered& a, const Rendered& b) {
    double s = rmse(a.steady, b.steady);
    for (size_t f = 0; f < a.frames.size(); ++f) s += rmse(a.frames[f], b.frames[f]);
    return s / static_cast<double>(a.frames.size() + 1);
}

TEST(ImportRender, CornellBoxAsJsonObjAndGltfAgree) {
    TempDir dir;
    std::vector<ModelMaterial> mats;
    ModelMesh mesh = cornell_mesh(mats);
    write_obj(dir.file("box.obj"), "box.mtl", mesh, mats);
    // glTF: the light is an emissive quad of the file itself (black, one-sided, facing down).
    ModelMesh with_light = mesh;
    std::vector<ModelMaterial> mats_light = mats;
    mats_light.push_back({"lamp", Vec3(0), {17, 12, 4}});
    LightDesc l = cornell_light();
    with_light.quad(l.corner, l.edge1, l.edge2, 3);
    write_gltf(dir.file("box.gltf"), with_light, mats_light, false);
    write_gltf(dir.file("box.glb"), with_light, mats_light, true);

    const Rendered json1 = render_all(cornell_json(1));
    const Rendered json2 = render_all(cornell_json(2));
    SceneDesc obj = with_file(cornell_base(1), ShapeType::Mesh, dir.file("box.obj"));
    obj.lights.push_back(cornell_light());
    const Rendered from_obj = render_all(obj);
    const Rendered from_gltf = render_all(with_file(cornell_base(1), ShapeType::Gltf, dir.file("box.gltf")));
    const Rendered from_glb = render_all(with_file(cornell_base(1), ShapeType::Gltf, dir.file("box.glb")));

    const double seed_spread = difference(json1, json2);
    const double d_obj = difference(json1, from_obj), d_gltf = difference(json1, from_gltf);
    std::printf("seed-to-seed %.4g, JSON vs OBJ %.4g, JSON vs glTF %.4g, mean %.4g / %.4g / %.4g\n", seed_spread,
                d_obj, d_gltf, mean(json1.steady), mean(from_obj.steady), mean(from_gltf.steady));
    ASSERT_GT(seed_spread, 0);
    // Same triangles, same quad light, same seed: the OBJ renders (nearly) the same numbers.
    EXPECT_LT(d_obj, 0.05 * seed_spread);
    // An emissive quad instead of the quad light samples differently: within seed-to-seed noise.
    EXPECT_LT(d_gltf, 1.5 * seed_spread);
    EXPECT_NEAR(mean(from_gltf.steady), mean(json1.steady), 0.03 * mean(json1.steady));
    // .gltf + .bin and .glb are the same file.
    EXPECT_EQ(from_gltf.steady, from_glb.steady);
}

TEST(ImportRender, EmissiveQuadMeshEqualsQuadLight) {
    TempDir dir;
    // A floor lit by a 0.5 x 0.4 m panel facing down, 1 m above it.
    SceneDesc base = plane_under_point_light(0.7f, 0, 1, 1.5f, 24, 2);
    base.lights.clear();
    base.render.max_depth = 4;
    base.render.passes = 8;
    base.render.photons_per_pass = 20000;
    base.time = {0, 12, 8, 24};
    LightDesc l;
    l.type = LightType::Quad;
    l.corner = {-0.25f, 1, -0.2f};
    l.edge1 = {0.5f, 0, 0};
    l.edge2 = {0, 0, 0.4f};
    l.radiance = {10, 8, 6};
    SceneDesc with_light = base;
    with_light.lights.push_back(l);
    ModelMesh panel;
    panel.quad(l.corner, l.edge1, l.edge2, 0);
    write_gltf(dir.file("panel.glb"), panel, {{"panel", Vec3(0), l.radiance}}, true);
    const Rendered a = render_all(with_light);
    const Rendered b = render_all(with_file(base, ShapeType::Gltf, dir.file("panel.glb")));
    with_light.render.seed = 2;
    const Rendered a2 = render_all(with_light);
    const double spread = difference(a, a2), d = difference(a, b);
    std::printf("quad light vs emissive mesh %.4g, seed-to-seed %.4g, means %.5g / %.5g\n", d, spread, mean(a.steady),
                mean(b.steady));
    EXPECT_LT(d, 1.5 * spread);
    EXPECT_NEAR(mean(b.steady), mean(a.steady), 0.01 * mean(a.steady));
    for (size_t f = 0; f < a.frames.size(); ++f)
        EXPECT_NEAR(mean(b.frames[f]), mean(a.frames[f]), 0.02 * mean(a.steady) + 1e-9) << "frame " << f;
    // The camera sees the panel's front only from below: here it looks down on its back.
}

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

TEST(ImportRender, TexturedPlaneFollowsAnalyticDirectLight) {
    TempDir dir;
    // 16 x 16 texels, 4 x 4 checker squares of 4 texels: inside a square's middle, bilinear
    // filtering returns the square's own value.
    const uint8_t bright = 200, dark = 60;
    std::vector<uint8_t> rgb(16 * 16 * 3);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            for (int c = 0; c < 3; ++c) rgb[(y * 16 + x) * 3 + c] = ((x / 4 + y / 4) % 2) ? dark : bright;
    write_png(dir.file("checker.png"), 16, 16, rgb.data());
    ModelMesh plane;
    plane.quad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0);
    write_obj(dir.file("plane.obj"), "plane.mtl", plane, {{"checker", Vec3(1), Vec3(0), "checker.png"}});
    const float P = 100, h = 0.8f;
    const int res = 32;
    SceneDesc s = plane_under_point_light(0.5f, P, h, 1, res, 1);
    s.shapes.clear();
    s.shapes.push_back(with_file(SceneDesc{}, ShapeType::Mesh, dir.file("plane.obj")).shapes[0]);
    // Jittered pixel samples average cos/r^2 over the pixel: enough of them for ~0.5% noise.
    s.render.passes = 256;
    s.render.photons_per_pass = 100;
    const Rendered r = render_all(s);
    int checked = 0;
    double worst = 0;
    for (int j = 0; j < res; ++j)
        for (int i = 0; i < res; ++i) {
            // The pixel's centre on the plane (camera 1 m above, 90 degrees: the image is the plane).
            const double x = 2 * (i + 0.5) / res - 1, z = -(1 - 2 * (j + 0.5) / res);
            const double u = (x + 1) / 2 * 16, v = (z + 1) / 2 * 16;  // in texels
            const double fu = std::fmod(u, 4), fv = std::fmod(v, 4);
            if (fu < 1.5 || fu > 2.5 || fv < 1.5 || fv > 2.5) continue;  // near a square's edge
            const int sx = static_cast<int>(u / 4), sy = static_cast<int>(v / 4);
            const double albedo = srgb_to_linear(((sx + sy) % 2 ? dark : bright) / 255.0);
            const double r2 = x * x + z * z + h * h, cos_t = h / std::sqrt(r2);
            const double expected = albedo / M_PI * (P / (4 * M_PI)) * cos_t / r2;
            const double got = r.steady[(static_cast<size_t>(j) * res + i) * 3 + 1];
            worst = std::max(worst, std::abs(got / expected - 1));
            ++checked;
        }
    std::printf("%d pixels in checker squares, worst relative error %.4f\n", checked, worst);
    EXPECT_GE(checked, 32);
    EXPECT_LT(worst, 0.015);
    // The same plane as .gltf (external PNG) and .glb (the PNG inside): the same image.
    ModelMesh gplane;
    gplane.quad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0);
    std::vector<ModelMaterial> gm = {{"checker", Vec3(1), Vec3(0), "checker.png"}};
    write_gltf(dir.file("plane.gltf"), gplane, gm, false);
    write_gltf(dir.file("plane.glb"), gplane, gm, true);
    for (const char* f : {"plane.gltf", "plane.glb"}) {
        s.shapes[0].type = ShapeType::Gltf;
        s.shapes[0].file = dir.file(f);
        s.shapes[0].mesh = nullptr;
        const Rendered g = render_all(s);
        EXPECT_LT(rmse(g.steady, r.steady), 1e-3 * mean(r.steady)) << f;
    }
}

// A UV sphere of radius 1 at the origin, with or without its vertex normals.
void write_sphere(const std::string& path, int segments, bool normals) {
    ModelMesh m;
    const int rings = segments / 2;
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s <= segments; ++s) {
            double th = M_PI * r / rings, ph = 2 * M_PI * s / segments;
            Vec3 p(static_cast<float>(std::sin(th) * std::cos(ph)), static_cast<float>(std::cos(th)),
                   static_cast<float>(-std::sin(th) * std::sin(ph)));
            m.positions.push_back(p);
            m.normals.push_back(p);
            m.uvs.insert(m.uvs.end(), {0, 0});
        }
    auto at = [&](int r, int s) { return static_cast<uint32_t>(r * (segments + 1) + s); };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            m.indices.insert(m.indices.end(), {at(r, s), at(r + 1, s), at(r + 1, s + 1)});
            m.indices.insert(m.indices.end(), {at(r, s), at(r + 1, s + 1), at(r, s + 1)});
            m.tri_material.insert(m.tri_material.end(), {0, 0});
        }
    write_obj(path, "sphere.mtl", m, {{"grey", Vec3(0.8f)}}, normals);
}

TEST(ImportRender, SmoothSphereMatchesAnalyticSphereAndFlatDoesNot) {
    TempDir dir;
    write_sphere(dir.file("smooth.obj"), 48, true);
    write_sphere(dir.file("flat.obj"), 48, false);
    SceneDesc s;
    s.source = "<sphere>";
    s.camera.position = {0, 0, 4};
    s.camera.look_at = {0, 0, 0};
    s.camera.vfov_deg = 32;
    s.camera.width = s.camera.height = 48;
    MaterialDesc grey;
    grey.albedo = Vec3(0.8f);
    s.materials.push_back(grey);
    LightDesc l;
    l.type = LightType::Point;
    l.position = {6, 4, 6};
    l.power = Vec3(2000);
    s.lights.push_back(l);
    s.render.max_depth = 1;
    s.render.passes = 4;
    s.render.photons_per_pass = 1000;
    SceneDesc analytic = s;
    ShapeDesc sphere;
    sphere.type = ShapeType::Sphere;
    sphere.radius = 1;
    analytic.shapes.push_back(sphere);
    SceneDesc smooth = s, flat = s;
    smooth.shapes.push_back(with_file(SceneDesc{}, ShapeType::Mesh, dir.file("smooth.obj")).shapes[0]);
    smooth.shapes.back().material = 0;
    flat.shapes.push_back(with_file(SceneDesc{}, ShapeType::Mesh, dir.file("flat.obj")).shapes[0]);
    flat.shapes.back().material = 0;
    const Rendered ra = render_all(analytic), rs = render_all(smooth), rf = render_all(flat);
    // Lit pixels well inside the silhouette: mean relative difference, and the worst.
    double sum_s = 0, sum_f = 0, worst_s = 0, brightest = 0;
    int n = 0;
    for (size_t p = 0; p < ra.steady.size() / 3; ++p) brightest = std::max<double>(brightest, ra.steady[3 * p + 1]);
    for (size_t p = 0; p < ra.steady.size() / 3; ++p) {
        const double a = ra.steady[3 * p + 1];
        const int x = static_cast<int>(p % 48), y = static_cast<int>(p / 48);
        const double dx = (x + 0.5) / 24 - 1, dy = (y + 0.5) / 24 - 1;
        if (dx * dx + dy * dy > 0.6 || a < 0.2 * brightest) continue;
        if (a <= 0 || rs.steady[3 * p + 1] <= 0) continue;
        sum_s += std::abs(rs.steady[3 * p + 1] / a - 1);
        sum_f += std::abs(rf.steady[3 * p + 1] / a - 1);
        worst_s = std::max(worst_s, std::abs(rs.steady[3 * p + 1] / a - 1));
        ++n;
    }
    ASSERT_GT(n, 100);
    std::printf("%d pixels: smooth mean %.4f worst %.4f, flat mean %.4f\n", n, sum_s / n, worst_s, sum_f / n);
    EXPECT_LT(sum_s / n, 0.005);
    EXPECT_GT(sum_f / n, 3 * sum_s / n);
}

}  // namespace
}  // namespace sl::test
