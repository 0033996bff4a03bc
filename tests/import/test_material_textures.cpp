// glTF's metallic-roughness texture, checked by a second path through the code: a floor whose
// texture makes one half smooth metal and the other rough plastic renders each half as the same
// two materials given by their factors alone (no texture) do.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "stages/output/png_io.h"
#include "tests/common/temp_dir.h"
#include "tests/import/model_writers.h"
#include "tests/render/render_helpers.h"
#include "tests/render/scenes_for_tests.h"

namespace sl::test {
namespace {

// The small box with its floor replaced by the glTF file `gltf` (x in [-1, 1], z in [-1, 1]).
SceneDesc box_with_floor(const std::string& gltf) {
    SceneDesc s = small_box(32, 4, 20000);
    s.shapes.erase(s.shapes.begin());
    s.shapes.push_back(model_shape(gltf, ShapeType::Gltf));
    return s;
}

// Mean of the image's lowest quarter (the floor: the camera looks level from 1 m up), in its
// left or right half.
double floor_mean(const Rendered& r, bool left, int margin) {
    double sum = 0;
    int n = 0;
    for (int y = 3 * r.height / 4; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            const bool is_left = x < r.width / 2 - margin, is_right = x >= r.width / 2 + margin;
            if (left ? !is_left : !is_right) continue;
            const size_t i = 3 * (static_cast<size_t>(y) * static_cast<size_t>(r.width) + static_cast<size_t>(x));
            sum += r.steady[i] + r.steady[i + 1] + r.steady[i + 2];
            ++n;
        }
    return sum / n;
}

ModelMaterial glossy(const std::string& name, float metallic, float roughness) {
    ModelMaterial m(name, {0.9f, 0.6f, 0.3f});
    m.metallic = metallic;
    m.roughness = roughness;
    m.specular = 1;
    return m;
}

TEST(MaterialTextures, MetallicRoughnessTextureHalvesRenderAsTheirUntexturedMaterials) {
    TempDir dir;
    // 64 x 1 texels: the left 32 smooth metal (G 51 = roughness 0.2, B 255 = metallic 1), the
    // right 32 rough plastic (G 153 = roughness 0.6, B 0 = metallic 0). R is unused (occlusion).
    std::vector<uint8_t> texels;
    for (int x = 0; x < 64; ++x) texels.insert(texels.end(), {0, static_cast<uint8_t>(x < 32 ? 51 : 153), static_cast<uint8_t>(x < 32 ? 255 : 0)});
    write_png(dir.file("mr.png"), 64, 1, texels.data());

    // The textured floor: one quad, u from 0 at x = -1 to 1 at x = 1; factors 1 (the texture decides).
    ModelMesh one;
    one.quad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0);
    ModelMaterial textured = glossy("textured", 1, 1);
    textured.metallic_roughness_image = "mr.png";
    write_gltf(dir.file("textured.gltf"), one, {textured}, false);
    // The same two materials by their factors, one quad each.
    ModelMesh two;
    two.quad({-1, 0, 1}, {1, 0, 0}, {0, 0, -2}, 0);
    two.quad({0, 0, 1}, {1, 0, 0}, {0, 0, -2}, 1);
    write_gltf(dir.file("factors.gltf"), two, {glossy("metal", 1, 0.2f), glossy("plastic", 0, 0.6f)}, false);
    // The textured material with its texture left out: rough metal everywhere.
    write_gltf(dir.file("untextured.gltf"), one, {glossy("rough metal", 1, 1)}, false);

    const Rendered t = render_all(box_with_floor(dir.file("textured.gltf")));
    const Rendered f = render_all(box_with_floor(dir.file("factors.gltf")));
    const Rendered u = render_all(box_with_floor(dir.file("untextured.gltf")));
    // The camera looks along -z: image left is x < 0. Two pixel columns either side of the
    // middle are left out (bilinear filtering blends the halves within a texel of the seam).
    for (bool left : {true, false}) {
        const double want = floor_mean(f, left, 2), got = floor_mean(t, left, 2), ignored = floor_mean(u, left, 2);
        SCOPED_TRACE(left ? "metal half" : "plastic half");
        std::printf("%s half: textured %.6g, factors %.6g, texture ignored %.6g\n", left ? "metal" : "plastic", got, want,
                    ignored);
        ASSERT_GT(want, 0);
        EXPECT_NEAR(got, want, 0.02 * want);
        // The check can fail: ignoring the texture gives a different number.
        EXPECT_GT(std::abs(ignored - want), 0.1 * want);
    }
}

}  // namespace
}  // namespace sl::test
