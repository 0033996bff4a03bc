// A pixel's light samples stratified over the passes (camera_pass.cpp, light_pass_point),
// checked where it matters: a soft shadow, where each sample either sees the lamp or not. The
// same mean as independent samples (the other way through the code), and far less spread from
// seed to seed; the penumbra's middle against the open floor's light as the geometry gives it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "light_paths_helpers.h"

namespace sl {
namespace {

// A grey floor z = 0 under a 1 x 1 m lamp 2 m up, and a black sheet at z = 1 over the half
// x < 0: a floor point at x in [-0.5, 0.5] sees the lamp's part beyond -x, a share 0.5 + x of
// it. The camera, 0.9 m up under the sheet, sees x and y in [-0.5, 0.5]: the whole penumbra.
std::vector<float> penumbra(bool stratified, uint64_t seed, int passes) {
    const int res = 16;
    const float vfov = 2 * std::atan(0.5f / 0.9f) * 180 / 3.14159265f;
    SceneDesc s = lp::empty_scene({0, 0, 0.9f}, {0, 0, 0}, {0, 1, 0}, vfov, res);
    const int grey = lp::add_material(s, MaterialType::Diffuse, Vec3(0.5f));
    const int black = lp::add_material(s, MaterialType::Diffuse, Vec3(0));
    lp::add_quad(s, {-3, -3, 0}, {6, 0, 0}, {0, 6, 0}, grey);
    lp::add_quad(s, {-3, -3, 1}, {0, 6, 0}, {3, 0, 0}, black);
    LightDesc l;
    l.type = LightType::Quad;
    l.corner = {-0.5f, -0.5f, 2};
    l.edge1 = {0, 1, 0};
    l.edge2 = {1, 0, 0};  // edge1 x edge2 = -z: it shines down
    l.radiance = Vec3(10);
    s.lights.push_back(l);
    // Direct light only (max_depth 1).
    return lp::steady_image(s, 1, passes, 1000, seed,
                            [&](RenderContext& ctx) { ctx.stratified_light_points = stratified; });
}

TEST(LightPoints, ASoftShadowConvergesFasterWithTheSameMean) {
    const int seeds = 12, passes = 64, res = 16;
    double image_mean[2] = {0, 0}, image_sd[2] = {0, 0}, pixel_sd[2] = {0, 0};
    std::vector<float> mean_image;
    for (int k = 0; k < 2; ++k) {
        std::vector<std::vector<float>> imgs;
        for (int s = 1; s <= seeds; ++s) imgs.push_back(penumbra(k == 1, static_cast<uint64_t>(s), passes));
        const size_t n = imgs[0].size();
        std::vector<double> means;
        for (const auto& img : imgs) {
            double sum = 0;
            for (float v : img) sum += v;
            means.push_back(sum / static_cast<double>(n));
        }
        for (double m : means) image_mean[k] += m / seeds;
        for (double m : means) image_sd[k] += (m - image_mean[k]) * (m - image_mean[k]) / (seeds - 1);
        image_sd[k] = std::sqrt(image_sd[k]);
        // Each pixel's spread over the seeds, relative to the image's mean, averaged over pixels.
        for (size_t i = 0; i < n; ++i) {
            double m = 0, q = 0;
            for (const auto& img : imgs) m += img[i] / seeds;
            for (const auto& img : imgs) q += (img[i] - m) * (img[i] - m) / (seeds - 1);
            pixel_sd[k] += std::sqrt(q) / image_mean[k] / static_cast<double>(n);
        }
        if (k == 1) {
            mean_image.assign(n, 0);
            for (const auto& img : imgs)
                for (size_t i = 0; i < n; ++i) mean_image[i] += img[i] / seeds;
        }
    }
    std::printf("penumbra, %d passes, %d seeds: image mean %.5f (independent) vs %.5f (stratified); pixel spread "
                "%.4f vs %.4f (%.1fx less)\n",
                passes, seeds, image_mean[0], image_mean[1], pixel_sd[0], pixel_sd[1], pixel_sd[0] / pixel_sd[1]);
    // The same mean within 4 combined standard errors of the seeds' image means.
    const double combined = std::sqrt((image_sd[0] * image_sd[0] + image_sd[1] * image_sd[1]) / seeds);
    EXPECT_NEAR(image_mean[1], image_mean[0], 4 * combined);
    // Independent samples leave each pixel a binomial share of the lamp (10 % at 64 passes);
    // stratified, the share's error falls nearly as 1/passes (measured: 4.1x less here, 2.3x at 16 passes).
    EXPECT_GT(pixel_sd[0], 3 * pixel_sd[1]);
    // Against the geometry: a floor point's irradiance is L h^2 / r^4 integrated over the lamp's
    // visible part (lx > -x), here by the midpoint rule over each pixel's floor and the lamp.
    // The penumbra's middle (the two columns either side of x = 0) against the open floor's
    // edge (column 15, x near +0.47, which sees 97 % of the lamp from 0.47 m off its axis).
    auto irradiance_over_pixel = [&](int col, int row) {
        const int sub = 4, lamp = 100;
        double e = 0;
        for (int a = 0; a < sub; ++a)
            for (int b = 0; b < sub; ++b) {
                const double x = -0.5 + (col + (a + 0.5) / sub) / res, y = 0.5 - (row + (b + 0.5) / sub) / res;
                for (int i = 0; i < lamp; ++i) {
                    const double lx = -0.5 + (i + 0.5) / lamp;
                    if (lx < -x) continue;  // behind the sheet's edge
                    for (int j = 0; j < lamp; ++j) {
                        const double ly = -0.5 + (j + 0.5) / lamp, r2 = (lx - x) * (lx - x) + (ly - y) * (ly - y) + 4;
                        e += 4 / (r2 * r2);
                    }
                }
            }
        return e;
    };
    double middle = 0, edge = 0, expect_middle = 0, expect_edge = 0;
    for (int y = 4; y < 12; ++y) {
        middle += mean_image[(size_t(y) * res + 7) * 3] + mean_image[(size_t(y) * res + 8) * 3];
        edge += 2 * mean_image[(size_t(y) * res + 15) * 3];
        expect_middle += irradiance_over_pixel(7, y) + irradiance_over_pixel(8, y);
        expect_edge += 2 * irradiance_over_pixel(15, y);
    }
    std::printf("penumbra's middle / open edge: %.4f (geometry %.4f)\n", middle / edge, expect_middle / expect_edge);
    EXPECT_NEAR(middle / edge, expect_middle / expect_edge, 0.02);
}

}  // namespace
}  // namespace sl
