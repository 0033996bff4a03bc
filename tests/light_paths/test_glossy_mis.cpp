// Multiple importance sampling at the glossy vertices camera paths follow (camera_pass.cpp):
// direct light from an area emitter is the light samples plus the followed direction's hits on
// the emitter, each weighed by the power heuristic. The expected radiance is a quadrature of the
// GGX formula over the emitter, written out here again (not from core/bsdf/); the second check
// is the point of it: a sharp lobe left to light samples alone has a spread over pixels that
// MIS cuts several times, at the same mean.
#include <gtest/gtest.h>

#include <cmath>

#include "light_paths_helpers.h"

namespace sl {
namespace {

double ggx_d(double alpha, double cos_h) {
    const double a2 = alpha * alpha, c2 = cos_h * cos_h, den = c2 * (a2 - 1) + 1;
    return a2 / (M_PI * den * den);
}
double smith_lambda(double alpha, double c) {
    return (-1 + std::sqrt(1 + alpha * alpha * (1 - c * c) / (c * c))) / 2;
}
// A white conductor (F = 1): D G2 / (4 cos_o cos_i) about +z.
double white_metal_f(double alpha, Vec3 wo, Vec3 wi) {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    const Vec3 h = normalize(wo + wi);
    return ggx_d(alpha, h.z) / (1 + smith_lambda(alpha, wo.z) + smith_lambda(alpha, wi.z)) / (4 * wo.z * wi.z);
}

constexpr float kRoughness = 0.2f, kRadiance = 2.0f, kHeight = 1.0f, kSide = 3.0f;
const Vec3 kCam{-0.7f, 0, 0.45f};

// A rough white metal floor z = 0 under a square emitter (a quad light facing down, kSide wide,
// kHeight up, centred above the origin); the camera sees the floor where the emitter's mirror
// image lies. Nothing else: every pixel's light is the emitter reflected once.
SceneDesc mirror_under_emitter() {
    SceneDesc s = lp::empty_scene(kCam, {0.2f, 0, 0}, {0, 0, 1}, 40, 24);
    MaterialDesc m;
    m.name = "white_metal";
    m.type = MaterialType::Conductor;
    m.reflectance = Vec3(1);
    m.roughness = kRoughness;
    s.materials.push_back(m);
    lp::add_quad(s, {-4, -4, 0}, {8, 0, 0}, {0, 8, 0}, 0);
    LightDesc l;
    l.type = LightType::Quad;
    l.corner = {-kSide / 2, kSide / 2, kHeight};
    l.edge1 = {kSide, 0, 0};
    l.edge2 = {0, -kSide, 0};  // edge1 x edge2 = -z: the front faces the floor
    l.radiance = Vec3(kRadiance);
    s.lights.push_back(l);
    s.time = {0, 12, 12, 24};
    s.emission.mode = EmissionMode::Constant;
    s.render.max_depth = 3;
    s.render.passes = 48;
    s.render.photons_per_pass = 1000;
    return s;
}

// L at floor point p seen from the camera: int f cos_i L dw over the emitter, by the midpoint
// rule on an n x n grid of it (cos_i cos_l / d^2 dA).
double expected_radiance(Vec3 p, int n) {
    const Vec3 wo = normalize(kCam - p);
    const double alpha = kRoughness * kRoughness, da = (kSide / n) * (kSide / n);
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const Vec3 q{-kSide / 2 + kSide * (i + 0.5f) / n, -kSide / 2 + kSide * (j + 0.5f) / n, kHeight};
            const Vec3 v = q - p;
            const double d2 = dot(v, v);
            const Vec3 wi = v / std::sqrt(static_cast<float>(d2));
            sum += white_metal_f(alpha, wo, wi) * wi.z * wi.z / d2 * da;  // cos_l = wi.z too
        }
    return sum * kRadiance;
}

struct Spread {
    double ratio = 0, rms = 0;  // summed rendered / summed expected; the pixels' rms error / their mean
    int pixels = 0;
};

Spread render_against_quadrature(bool mis, int split) {
    const SceneDesc s = mirror_under_emitter();
    RenderContext ctx(with_imports(s));
    ctx.glossy_mis = mis;
    ctx.glossy_split = split;
    FramesInMemory sink;
    render_frames(ctx, {}, sink);
    const PinholeCamera cam(s.camera);
    const int w = s.camera.width;
    double got = 0, want = 0, sq = 0;
    Spread r;
    for (int y = 0; y < s.camera.height; ++y)
        for (int x = 0; x < w; ++x) {
            double l = 0;  // the pixel's mean, over 2 x 2 points of it (the renderer jitters)
            for (int k = 0; k < 4; ++k)
                l += expected_radiance(lp::on_plane(cam, x + (k % 2 + 0.5f) / 2, y + (k / 2 + 0.5f) / 2, {0, 0, 1}, 0),
                                       240) / 4;
            if (!(l > 0.05 * kRadiance)) continue;  // where the lobe sees the emitter
            const double g = sink.steady[(static_cast<size_t>(y) * w + x) * 3];
            got += g;
            want += l;
            sq += (g - l) * (g - l);
            ++r.pixels;
        }
    r.ratio = got / want;
    r.rms = std::sqrt(sq / std::max(1, r.pixels)) / (want / std::max(1, r.pixels));
    return r;
}

TEST(GlossyMis, RoughMetalUnderAnEmitterMatchesQuadratureWithASmallerSpread) {
    const Spread with = render_against_quadrature(true, 1), without = render_against_quadrature(false, 1);
    ASSERT_GT(with.pixels, 150);
    EXPECT_NEAR(with.ratio, 1.0, 0.015);
    // Light samples alone have the same mean, but their weight f cos / p_light is heavy-tailed
    // under a sharp lobe: their sum approaches it from below, slowly (not checked).
    EXPECT_LT(with.rms * 5, without.rms);
    std::printf("[glossy MIS, rough white metal (roughness %.1f) under a %.0f m emitter] rendered / quadrature: MIS "
                "%.4f (pixels' rms error / mean %.4f), light samples alone %.4f (rms %.4f), over %d pixels\n",
                kRoughness, kSide, with.ratio, with.rms, without.ratio, without.rms, with.pixels);
}

// The camera path split at its first followed glossy vertex (RenderContext::glossy_split, the
// program's 8 at a metal): the same mean, n directions there weighed against the light sample as
// one strategy of n times the density, and a smaller spread. The 8 draws are stratified
// (core/glossy_path.h): the spread falls by more than 3x (8 independent draws: 0.028 against
// the unsplit path's 0.078, 2.8x; stratified 0.018).
TEST(GlossyMis, APathSplitAtTheGlossyVertexKeepsTheMeanWithASmallerSpread) {
    const Spread one = render_against_quadrature(true, 1), split = render_against_quadrature(true, 8);
    EXPECT_NEAR(split.ratio, 1.0, 0.01);
    EXPECT_LT(split.rms * 3, one.rms);
    std::printf("[glossy MIS, the path split in 8 stratified draws at the metal] rendered / quadrature %.4f (pixels' rms error / "
                "mean %.4f; unsplit %.4f, rms %.4f)\n",
                split.ratio, split.rms, one.ratio, one.rms);
}

}  // namespace
}  // namespace sl
