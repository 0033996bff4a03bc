// The beam estimate from the photons' side (stages/render/beam_splat.h) against the search of
// the volume BVH along each segment: the same photons and kernel, so the same images up to the
// order of the sums; and the camera's bound on the pixels that may take a photon, against the
// pixels' own rays.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/camera.h"
#include "core/rng.h"
#include "render_helpers.h"
#include "scenes_for_tests.h"

namespace sl {
namespace {

// The largest difference between two renders' pixels, over the frame's largest pixel, over
// every frame; and that largest pixel's sum over the frames (so a test can see light is there).
struct Difference {
    double worst = 0, light = 0;
};
Difference compare(const test::Rendered& a, const test::Rendered& b) {
    Difference d;
    for (size_t f = 0; f < a.frames.size(); ++f) {
        float peak = 0, diff = 0;
        for (size_t i = 0; i < a.frames[f].size(); ++i) {
            peak = std::max(peak, std::fabs(a.frames[f][i]));
            diff = std::max(diff, std::fabs(a.frames[f][i] - b.frames[f][i]));
        }
        d.light += peak;
        if (peak > 0) d.worst = std::max(d.worst, static_cast<double>(diff / peak));
    }
    return d;
}

Difference splat_against_search(const SceneDesc& s) {
    const auto splat = test::render_switched(s, [](RenderContext& ctx) { ctx.beam_splat = true; });
    const auto search = test::render_switched(s, [](RenderContext& ctx) { ctx.beam_splat = false; });
    return compare(splat, search);
}

// The Cornell-like box of the tests filled with haze, seen through a wide, oblong image (the
// bound's corners), a flash (each photon in its own frame).
SceneDesc hazy_box(int w, int h) {
    SceneDesc s = test::small_box(w, 3, 20000, 6);
    s.camera.width = w;
    s.camera.height = h;
    s.camera.vfov_deg = 80;
    s.medium.present = true;
    s.medium.sigma_a = Vec3(0.05f);
    s.medium.sigma_s = {0.8f, 0.6f, 0.4f};
    s.medium.g = 0.4f;
    s.emission.mode = EmissionMode::Pulse;
    // A panel in the haze: photons behind it are in the image's box but behind the pixels' ends.
    s.shapes.push_back(test::quad({-0.6f, 0.6f, -0.3f}, {0.8f, 0, 0}, {0, 0.8f, 0}, 0));
    return s;
}

TEST(BeamSplat, GivesTheImagesOfTheSearchAlongEverySegmentWithTheCameraInTheHaze) {
    const Difference d = splat_against_search(hazy_box(72, 40));
    std::printf("camera in the haze: largest difference %.2e of a frame's brightest pixel\n", d.worst);
    EXPECT_GT(d.light, 0);
    EXPECT_LT(d.worst, 2e-5);
}

TEST(BeamSplat, GivesTheImagesOfTheSearchWithTheHazeAwayFromTheCamera) {
    // The haze fills the box's far half: each segment starts where the ray enters it.
    SceneDesc s = hazy_box(64, 48);
    s.medium.has_bounds = true;
    s.medium.bounds_min = {-1, 0, -1};
    s.medium.bounds_max = {1, 2, 0.2f};
    const Difference d = splat_against_search(s);
    std::printf("haze away from the camera: largest difference %.2e\n", d.worst);
    EXPECT_GT(d.light, 0);
    EXPECT_LT(d.worst, 2e-5);
}

TEST(BeamSplat, GivesTheImagesOfTheSearchWhenPhotonsSpanTheWholeImage) {
    // A radius of a third of the box: photons near the camera reach every pixel (the wide list).
    SceneDesc s = hazy_box(40, 80);
    s.render.radius = 0.6f;
    const Difference d = splat_against_search(s);
    std::printf("wide photons: largest difference %.2e\n", d.worst);
    EXPECT_GT(d.light, 0);
    EXPECT_LT(d.worst, 2e-5);
}

// Every ray through a pixel that passes within rho of c is in PinholeCamera::pixels_near's box.
TEST(BeamSplat, TheCamerasBoundHoldsEveryPixelWhoseRayPassesNearAPoint) {
    CameraDesc cd;
    cd.position = {0.3f, 1.1f, -0.4f};
    cd.look_at = {2, 0.5f, -6};
    cd.up = {0, 1, 0};
    cd.vfov_deg = 75;
    cd.width = 48;
    cd.height = 27;
    const PinholeCamera cam(cd);
    Rng rng(3, 0, 0, 0);
    int inside = 0, checked = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const Vec3 c = cam.position() + Vec3(rng.uniform() * 8 - 4, rng.uniform() * 8 - 4, -rng.uniform() * 10 + 1);
        const float rho = 0.02f + 0.8f * rng.uniform() * rng.uniform();
        int x0 = 0, x1 = -1, y0 = 0, y1 = -1;
        const bool any = cam.pixels_near(c, rho, x0, x1, y0, y1);
        for (int y = 0; y < cd.height; ++y)
            for (int x = 0; x < cd.width; ++x)
                for (int k = 0; k < 4; ++k) {
                    const float fx = static_cast<float>(x) + rng.uniform(), fy = static_cast<float>(y) + rng.uniform();
                    const Vec3 d = cam.direction(fx, fy), v = c - cam.position();
                    const float s = dot(v, d);
                    if (!(s >= 0) || length(v - d * s) >= rho) continue;
                    ++checked;
                    const bool in_box = any && x >= x0 && x <= x1 && y >= y0 && y <= y1;
                    EXPECT_TRUE(in_box) << "pixel " << x << "," << y << " trial " << trial;
                    inside += in_box;
                }
    }
    std::printf("%d rays near a ball, %d inside its box\n", checked, inside);
    EXPECT_GT(checked, 1000);
}

}  // namespace
}  // namespace sl
