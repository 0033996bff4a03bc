// Normal maps (glTF normalTexture, MTL norm): the shading normal they make is the one BSDFs,
// direct light and photon bounces use.
// - Analytic: a flat plane with a constant tilted map under a point light (direct light only)
//   shows rho/pi * I cos(wi, n_map) / r^2 per pixel, n_map decoded from the texel bytes and
//   placed in the frame of the UV derivatives (glTF and OBJ) or of the TANGENT attribute.
// - Second path through the code: a room whose metal floor has that map renders as the same room
//   whose floor has the tilted normal as its vertex normals (camera paths and photons).
// - A neutral map (128, 128, 255) renders as no map.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <vector>

#include "stages/output/png_io.h"
#include "tests/common/temp_dir.h"
#include "tests/import/model_writers.h"
#include "tests/render/render_helpers.h"
#include "tests/render/scenes_for_tests.h"

namespace sl::test {
namespace {

constexpr uint8_t kTexel[3] = {166, 179, 238};  // tangent space ~ (0.30, 0.40, 0.87)

// The tangent-space normal a texel stands for: 2c - 1, normalised.
Vec3 decoded(const uint8_t c[3]) {
    return normalize(Vec3(2 * c[0] / 255.0f - 1, 2 * c[1] / 255.0f - 1, 2 * c[2] / 255.0f - 1));
}

void write_constant_map(const std::string& path, const uint8_t c[3]) {
    std::vector<uint8_t> px;
    for (int i = 0; i < 16; ++i) px.insert(px.end(), {c[0], c[1], c[2]});
    write_png(path, 4, 4, px.data());
}

// The 2 m floor at y = 0: u along +x, v along +z (glTF's v runs down the image: "up" is -z).
ModelMesh floor_mesh() {
    ModelMesh m;
    m.quad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0);
    return m;
}

ShapeDesc import(const std::string& file, ShapeType type) {
    ShapeDesc sh;
    sh.type = type;
    sh.file = file;
    sh.material = -1;
    return sh;
}

// Each pixel against rho/pi * P/(4 pi) cos / r^2, where the expected light is more than a
// fifth of the brightest (the terminator's pixels average across it).
void expect_lambert_cosine(const Rendered& r, float rho, float P, Vec3 light, float cam_h, Vec3 n) {
    const int res = r.width;
    std::vector<double> want(static_cast<size_t>(res * res));
    double peak = 0;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            double e = 0;  // the pixel's mean over 8 x 8 points of it
            for (int j = 0; j < 64; ++j) {
                const float fx = x + (j % 8 + 0.5f) / 8, fy = y + (j / 8 + 0.5f) / 8;
                const Vec3 to = light - Vec3(cam_h * (2 * fx / res - 1), 0, cam_h * (2 * fy / res - 1));
                e += std::max(0.0f, dot(normalize(to), n)) / dot(to, to) / 64;
            }
            want[static_cast<size_t>(y * res + x)] = rho / kPiDouble * P / (4 * kPiDouble) * e;
            peak = std::max(peak, want[static_cast<size_t>(y * res + x)]);
        }
    int checked = 0;
    for (size_t i = 0; i < want.size(); ++i) {
        if (want[i] < 0.2 * peak) continue;
        EXPECT_NEAR(r.steady[3 * i], want[i], 0.02 * want[i]) << "pixel " << i % res << ", " << i / res;
        ++checked;
    }
    EXPECT_GT(checked, res * res / 2);
}

TEST(NormalMaps, TiltedMapGivesLambertsCosineAboutTheMappedNormal) {
    TempDir dir;
    write_constant_map(dir.file("tilt.png"), kTexel);
    const Vec3 ts = decoded(kTexel);
    const float rho = 0.6f, P = 40, cam_h = 1;
    const Vec3 light{0.3f, 1.0f, 0.2f};
    auto scene = [&](const ShapeDesc& floor) {
        SceneDesc s = plane_under_point_light(rho, P, 1, cam_h, 24, 1);
        s.lights[0].position = light;
        s.shapes = {floor};
        s.render.passes = 64;  // the pixel's area: jittered
        return s;
    };
    // Tangent +x, bitangent -z (up the image), normal +y.
    const Vec3 n_uv{ts.x, ts.z, -ts.y};
    {  // glTF, tangents from the UVs; a metallic-roughness surface without a specular layer (Lambert).
        ModelMaterial mat("floor", Vec3(rho));
        mat.normal_image = "tilt.png";
        write_gltf(dir.file("uv.gltf"), floor_mesh(), {mat}, false);
        SCOPED_TRACE("glTF, tangents from the UVs");
        expect_lambert_cosine(render_all(scene(import(dir.file("uv.gltf"), ShapeType::Gltf))), rho, P, light, cam_h, n_uv);
    }
    {  // glTF with a TANGENT attribute turning the frame: tangent -z, so the bitangent is -x.
        ModelMesh m = floor_mesh();
        for (int i = 0; i < 4; ++i) m.tangents.insert(m.tangents.end(), {0, 0, -1, 1});
        ModelMaterial mat("floor", Vec3(rho));
        mat.normal_image = "tilt.png";
        write_gltf(dir.file("tangent.gltf"), m, {mat}, false);
        SCOPED_TRACE("glTF, TANGENT");
        expect_lambert_cosine(render_all(scene(import(dir.file("tangent.gltf"), ShapeType::Gltf))), rho, P, light,
                              cam_h, Vec3(-ts.y, ts.z, -ts.x));
    }
    {  // OBJ/MTL `norm` on a diffuse material.
        write_obj(dir.file("floor.obj"), "floor.mtl", floor_mesh(), {{"floor", Vec3(rho)}});
        std::ofstream(dir.file("floor.mtl"), std::ios::app) << "norm tilt.png\n";
        SCOPED_TRACE("OBJ norm");
        expect_lambert_cosine(render_all(scene(import(dir.file("floor.obj"), ShapeType::Mesh))), rho, P, light, cam_h, n_uv);
    }
}

// The small box with its floor replaced by `floor`.
SceneDesc box_with(const ShapeDesc& floor) {
    SceneDesc s = small_box(24, 8, 20000);
    s.shapes.erase(s.shapes.begin());
    s.shapes.push_back(floor);
    return s;
}

double channel_sum(const Rendered& r) {
    double s = 0;
    for (float v : r.steady) s += v;
    return s;
}

TEST(NormalMaps, MapRendersAsTheSameTiltInVertexNormals) {
    TempDir dir;
    write_constant_map(dir.file("tilt.png"), kTexel);
    const Vec3 ts = decoded(kTexel), n{ts.x, ts.z, -ts.y};
    // Glossy metal, which camera paths and photons both follow (core/material_table.h): direct
    // light at the floor, the camera's bounce and the photons' bounce all see the tilt, and the
    // walls gather what the floor sends them. (A surface that gathers is not compared: its
    // visible points keep the interpolated normal for the gather's geometry, by design.)
    ModelMaterial plastic("floor", {0.9f, 0.7f, 0.5f});
    plastic.metallic = 1;
    plastic.roughness = 0.3f;
    plastic.specular = 1;
    ModelMaterial mapped = plastic;
    mapped.normal_image = "tilt.png";
    write_gltf(dir.file("mapped.gltf"), floor_mesh(), {mapped}, false);
    ModelMesh tilted = floor_mesh();
    for (Vec3& v : tilted.normals) v = n;
    write_gltf(dir.file("tilted.gltf"), tilted, {plastic}, false);
    write_gltf(dir.file("flat.gltf"), floor_mesh(), {plastic}, false);
    const Rendered a = render_all(box_with(import(dir.file("mapped.gltf"), ShapeType::Gltf)));
    const Rendered b = render_all(box_with(import(dir.file("tilted.gltf"), ShapeType::Gltf)));
    const Rendered f = render_all(box_with(import(dir.file("flat.gltf"), ShapeType::Gltf)));
    std::printf("room with a tilted floor: normal map %.6g, vertex normals %.6g, flat %.6g\n", channel_sum(a),
                channel_sum(b), channel_sum(f));
    EXPECT_NEAR(channel_sum(a), channel_sum(b), 0.01 * channel_sum(b));
    EXPECT_LT(rmse(a.steady, b.steady), 0.25 * rmse(f.steady, b.steady));  // the tilt shows; the map gives it
}

TEST(NormalMaps, NeutralMapRendersAsNoMap) {
    TempDir dir;
    const uint8_t neutral[3] = {128, 128, 255};
    write_constant_map(dir.file("flat.png"), neutral);
    ModelMaterial plain("floor", {0.7f, 0.5f, 0.3f});
    plain.roughness = 0.4f;
    plain.specular = 1;
    ModelMaterial mapped = plain;
    mapped.normal_image = "flat.png";
    write_gltf(dir.file("mapped.gltf"), floor_mesh(), {mapped}, false);
    write_gltf(dir.file("plain.gltf"), floor_mesh(), {plain}, false);
    const Rendered a = render_all(box_with(import(dir.file("mapped.gltf"), ShapeType::Gltf)));
    const Rendered b = render_all(box_with(import(dir.file("plain.gltf"), ShapeType::Gltf)));
    // 128/255 is 0.0039 off 0.5: the map tilts the normal by 0.3 degrees.
    EXPECT_NEAR(channel_sum(a), channel_sum(b), 0.005 * channel_sum(b));
    EXPECT_LT(rmse(a.steady, b.steady), 0.02 * mean(b.steady));
}

}  // namespace
}  // namespace sl::test
