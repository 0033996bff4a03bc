// Single scattering by next-event estimation in the camera pass (issue 27): every frame of a
// render with max_depth 1 (nothing but single scattering) against an independent quadrature
// (single_scatter_reference.h), for each kind of light; the spread of the image's mean over
// seeds; the error falling with passes; segments after specular bounces; and the energy check
// that next-event estimation plus the volume photons of depth >= 2 equals the photons alone.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <functional>
#include <memory>

#include "core/import/mesh_data.h"
#include "render_helpers.h"
#include "single_scatter_reference.h"
#include "test_medium_scenes.h"

namespace sl {
namespace {

// With the switch that puts single scattering back on the volume photons (the estimator before
// next-event estimation).
test::Rendered render_mode(const SceneDesc& scene, bool by_photons) {
    return test::render_switched(scene, [by_photons](RenderContext& ctx) { ctx.single_scatter_by_photons = by_photons; });
}

// The issue's case at test size: a 300 W point light about 4 m from a camera inside an open fog
// (sigma_s 0.5, sigma_a 0.1 /m) 10 m across; here with RGB coefficients (a clear channel
// included) and g = 0.3, single scattering only. The light is behind the camera (out of view),
// so that the quadrature's few rays a pixel stay accurate; the light in view is a hard case.
SceneDesc haze_scene(bool tof, int res = 16) {
    SceneDesc s = test::light_in_open_medium(test::point_light({3.0f, 1.0f, -4.9f}, 300), {0.1f, 0.0f, 0.1f},
                                             {0.5f, 0.4f, 0.0f}, 0.3f, 5, {0, 0, -3.5f}, {0, 0, 1}, 60, res);
    s.time = {0, 40, 16, 24};  // 2.5 ns a frame
    s.render.photons_per_pass = 2000;
    s.render.passes = 8;
    s.render.camera_tof = tof;
    return s;
}

struct FrameErrors {
    std::vector<double> mean_dev;  // (render's frame mean) / (quadrature's) - 1, frames with light
    double pixel_rel = 0;          // sum |got - want| / sum want over pixels and frames
    double dark = 0;               // light where the quadrature has none, over the total
};

// Pixels whose rays pass within b of `light` (a near-singular peak that the quadrature's few rays
// a pixel cannot average): left out of the comparison.
std::vector<uint8_t> far_from(const SceneDesc& s, Vec3 light, float b) {
    PinholeCamera cam(s.camera);
    std::vector<uint8_t> use(static_cast<size_t>(s.camera.width) * s.camera.height, 1);
    for (int y = 0; y < s.camera.height; ++y)
        for (int x = 0; x < s.camera.width; ++x)
            for (int c = 0; c < 5; ++c) {
                const float fx = c == 4 ? 0.5f : float(c & 1), fy = c == 4 ? 0.5f : float(c >> 1);
                const Vec3 d = cam.direction(x + fx, y + fy), v = light - cam.position();
                const float sc = dot(v, d);
                const float dist = sc > 0 ? length(v - d * sc) : length(v);
                if (dist < b) use[static_cast<size_t>(y) * s.camera.width + x] = 0;
            }
    return use;
}

FrameErrors compare(const test::Rendered& r, const std::vector<std::vector<Vec3>>& want, double lit_fraction = 1e-3,
                    const std::vector<uint8_t>* use = nullptr) {
    FrameErrors e;
    const size_t frames = r.frames.size();
    double brightest = 0;
    std::vector<double> wsum(frames, 0), gsum(frames, 0);
    double abs_all = 0, want_all = 0, dark = 0;
    for (size_t k = 0; k < frames; ++k) {
        for (size_t p = 0; p < want.size(); ++p)
            for (int c = 0; c < 3; ++c) {
                if (use && !(*use)[p]) continue;
                const double w = want[p][k][c], g = r.frames[k][p * 3 + c];
                wsum[k] += w;
                gsum[k] += g;
                abs_all += std::abs(g - w);
                want_all += w;
                if (w == 0) dark += std::abs(g);
            }
        brightest = std::max(brightest, wsum[k]);
    }
    for (size_t k = 0; k < frames; ++k)
        if (wsum[k] > lit_fraction * brightest) e.mean_dev.push_back(gsum[k] / wsum[k] - 1);
    e.pixel_rel = abs_all / want_all;
    e.dark = dark / want_all;
    return e;
}

void print(const char* what, const FrameErrors& e) {
    std::printf("%s: pixel rel %.4f, dark %.2g, frame means:", what, e.pixel_rel, e.dark);
    for (double d : e.mean_dev) std::printf(" %+.4f", d);
    std::printf("\n");
}

double worst(const std::vector<double>& v) {
    double m = 0;
    for (double d : v) m = std::max(m, std::abs(d));
    return m;
}

std::vector<std::vector<Vec3>> point_reference(const SceneDesc& s, const test::QuadratureSetup& q) {
    const Timeline tl = timeline_of(s);
    const Vec3 I = s.lights[0].power * (1 / (4 * kPi));
    const auto b = test::single_scatter_buckets(s, tl, q, test::point_model(s.lights[0].position, [I](Vec3) { return I; }));
    return test::frames_of(b, tl, s.emission.mode);
}

void check_haze(bool tof) {
    SceneDesc s = haze_scene(tof);
    const auto want = point_reference(s, test::quadrature_setup(s));
    s.render.passes = 2;
    const FrameErrors e2 = compare(test::render_all(s), want);
    s.render.passes = 16;
    const FrameErrors e16 = compare(test::render_all(s), want);
    print(tof ? "haze, tof, 2 passes" : "haze, 2 passes", e2);
    print(tof ? "haze, tof, 16 passes" : "haze, 16 passes", e16);
    ASSERT_GE(e16.mean_dev.size(), 10u);
    EXPECT_LT(worst(e16.mean_dev), 0.01) << "every lit frame's mean within 1% of the quadrature";
    EXPECT_LT(e16.dark, 1e-6) << "nothing where no light can have arrived";
    // Noise per pixel falls as 1/sqrt(passes): 16 passes against 2, about 0.35.
    EXPECT_LT(e16.pixel_rel, 0.55 * e2.pixel_rel) << "the error must fall with passes";
}

TEST(SingleScatter, CameraInHazeEveryFrameMatchesQuadrature) { check_haze(false); }
TEST(SingleScatter, CameraInHazeEveryFrameMatchesQuadratureWithCameraTimeOfFlight) { check_haze(true); }

// The issue's measure: the steady image's mean over seeds (here 5 seeds, 32 passes, 32x32):
// single scattering no longer rests on the photons nearest the camera.
TEST(SingleScatter, SteadyImageMeanSpreadOverSeeds) {
    SceneDesc s = haze_scene(false, 32);
    s.render.passes = 32;
    double lo = 1e30, hi = -1e30;
    for (uint64_t seed = 1; seed <= 5; ++seed) {
        s.render.seed = seed;
        const double m = test::mean(test::render_all(s).steady);
        lo = std::min(lo, m);
        hi = std::max(hi, m);
    }
    std::printf("steady image mean over 5 seeds: spread (max - min) %.4f%%\n", 100 * (hi / lo - 1));
    EXPECT_LT(hi / lo - 1, 0.005);
}

// The issue's case: a 300 W point light in an open fog (sigma_s 0.5, sigma_a 0.1 /m, g 0) filling
// a 10 m box, the camera inside, 4 m from the light, which is in view; 96 x 96, max_depth 1.
SceneDesc issue_scene() {
    SceneDesc s = test::light_in_open_medium(test::point_light({0.8f, 0.5f, 1.5f}, 300), Vec3(0.1f), Vec3(0.5f), 0.0f, 5,
                                             {0, 0, -2.4f}, {0, 0, 1}, 60, 96);
    s.time = {0, 40, 16, 24};
    s.render.max_depth = 1;
    return s;
}

// The issue's measure with the light in view: the steady image's mean over 6 seeds at 64
// passes (photons carry nothing at max_depth 1, so 2000 a pass). The pixels round the light's
// image hold its 1/h in-scattering peak; with their rays stratified over the passes the spread
// is 0.19% (0.40% over 12 seeds); with independent uniform rays (and the disc drawn by chance)
// it was 0.85%.
TEST(SingleScatter, LightInViewImageMeanSpreadOverSeeds) {
    SceneDesc s = issue_scene();
    s.render.passes = 64;
    s.render.photons_per_pass = 2000;
    double lo = 1e30, hi = -1e30, sum = 0;
    for (uint64_t seed = 1; seed <= 6; ++seed) {
        s.render.seed = seed;
        const double m = test::mean(test::render_all(s).steady);
        lo = std::min(lo, m);
        hi = std::max(hi, m);
        sum += m;
    }
    const double spread = (hi - lo) / (sum / 6);
    std::printf("light in view: steady image mean over 6 seeds, spread (max - min) %.3f%%\n", 100 * spread);
    EXPECT_LT(spread, 0.006);
}

// The issue's own case, measured on request (not a suite test: minutes a seed):
// SL_HAZE_ISSUE="passes photons max_depth seeds", e.g. "64 200000 1 6": a 300 W point light in
// an open fog (sigma_s 0.5, sigma_a 0.1 /m, g 0) filling a 10 m box, the camera inside, 4 m from
// the light (in view), 96 x 96; prints the steady image's mean per seed and its spread.
TEST(SingleScatter, IssueCaseSpreadOnRequest) {
    const char* env = std::getenv("SL_HAZE_ISSUE");
    if (!env) {
        GTEST_SKIP() << "set SL_HAZE_ISSUE=\"passes photons max_depth seeds\"";
    }
    int passes = 0, depth = 0, seeds = 0;
    long long photons = 0;
    ASSERT_EQ(std::sscanf(env, "%d %lld %d %d", &passes, &photons, &depth, &seeds), 4);
    SceneDesc s = issue_scene();
    s.render.passes = passes;
    s.render.photons_per_pass = photons;
    s.render.max_depth = depth;
    double lo = 1e30, hi = -1e30, sum = 0, sum2 = 0;
    const std::vector<uint8_t> far = far_from(s, s.lights[0].position, 0.1f);
    for (int seed = 1; seed <= seeds; ++seed) {
        s.render.seed = static_cast<uint64_t>(seed);
        const test::Rendered r = test::render_all(s);
        const double m = test::mean(r.steady);
        double m_far = 0;
        for (size_t p = 0; p < far.size(); ++p)
            if (far[p]) m_far += r.steady[p * 3] + r.steady[p * 3 + 1] + r.steady[p * 3 + 2];
        // (the pixels whose rays pass within 0.1 m of the light carry its 1/h peak)
        std::printf("seed %d: steady image mean %.6g; the pixels' sum but those within 0.1 m of the light %.6g\n", seed,
                    m, m_far);
        lo = std::min(lo, m);
        hi = std::max(hi, m);
        sum += m;
        sum2 += m * m;
    }
    const double mean = sum / seeds, sd = std::sqrt(std::max(0.0, (sum2 - seeds * mean * mean) / (seeds - 1)));
    std::printf("spread (max - min) / mean %.3f%%, standard deviation %.3f%%\n", 100 * (hi - lo) / mean, 100 * sd / mean);
}

// A spot aimed at the camera, which sits in its cone: segments start in the beam and leave it.
TEST(SingleScatter, SpotAimedAtTheCamera) {
    LightDesc spot;
    spot.type = LightType::Spot;
    spot.position = {0.3f, 0.2f, 2.5f};
    spot.direction = {0, 0, -1};
    spot.cone_deg = 20;  // the half-angle (LightSet: cos_cone = cos(cone_deg))
    spot.power = Vec3(80);
    SceneDesc s = test::light_in_open_medium(spot, Vec3(0.05f), Vec3(0.3f), 0.2f, 5, {0, 0, -2}, {0, 0, 1}, 50, 16);
    s.time = {0, 30, 12, 24};
    s.render.photons_per_pass = 2000;
    s.render.passes = 16;
    const double cos_cone = std::cos(20 * kPiDouble / 180);
    const float I = static_cast<float>(80 / (2 * kPiDouble * (1 - cos_cone)));
    const Vec3 axis = spot.direction;
    const Timeline tl = timeline_of(s);
    test::QuadratureSetup q = test::quadrature_setup(s);
    q.sub = 4;  // the pixels near the spot's peak (1/b) need more than 2 x 2 rays
    const auto want = test::frames_of(
        test::single_scatter_buckets(s, tl, q, test::point_model(spot.position, [=](Vec3 w) {
            return dot(w, axis) >= cos_cone ? Vec3(I) : Vec3(0);
        })),
        tl, s.emission.mode);
    const std::vector<uint8_t> use = far_from(s, spot.position, 0.4f);
    const FrameErrors e = compare(test::render_all(s), want, 0.05, &use);
    print("spot at the camera (pixels whose rays pass >= 0.4 m from it)", e);
    // The first lit frame holds the light within 0.75 m of the spot, where a pixel's rays see
    // it vary as 1/b: the quadrature's 4 x 4 rays a pixel are good to a few percent there.
    ASSERT_GE(e.mean_dev.size(), 8u);
    EXPECT_LT(std::abs(e.mean_dev[0]), 0.05);
    for (size_t k = 1; k < e.mean_dev.size(); ++k) EXPECT_LT(std::abs(e.mean_dev[k]), 0.015) << "lit frame " << k;
}

// A 1 m x 0.8 m quad light above and behind a camera in the haze, facing down.
SceneDesc quad_in_haze() {
    LightDesc quad;
    quad.type = LightType::Quad;
    quad.corner = {-0.5f, 1.8f, -3.5f};  // above and behind the camera, out of view (rays end on it)
    quad.edge1 = {1.0f, 0, 0};
    quad.edge2 = {0, 0, 0.8f};  // edge1 x edge2 = -y: facing down
    quad.radiance = Vec3(30);
    SceneDesc s = test::light_in_open_medium(quad, Vec3(0.05f), Vec3(0.3f), 0.0f, 5, {0, 0, -2}, {0, 0, 1}, 50, 12);
    s.time = {0, 30, 12, 24};
    s.render.photons_per_pass = 2000;
    s.render.passes = 16;
    return s;
}

// The quadrature's frames for the scene's quad, split into 8 x 8 point-like pieces L A/64 cos.
std::vector<std::vector<Vec3>> quad_reference(const SceneDesc& s) {
    const LightDesc& quad = s.lights[0];
    const Timeline tl = timeline_of(s);
    test::QuadratureSetup q = test::quadrature_setup(s);
    q.steps = 1500;
    const int n = 8;
    const Vec3 normal = normalize(cross(quad.edge1, quad.edge2));
    const float piece = length(cross(quad.edge1, quad.edge2)) / (n * n);
    test::LightModel model = [&](Vec3 x, const std::function<void(const test::LightContribution&)>& add) {
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b) {
                const Vec3 at = quad.corner + quad.edge1 * ((a + 0.5f) / n) + quad.edge2 * ((b + 0.5f) / n);
                test::point_model(at, [&](Vec3 w) {
                    const float c = dot(w, normal);
                    return c > 0 ? quad.radiance * (piece * c) : Vec3(0);
                })(x, add);
            }
    };
    return test::frames_of(test::single_scatter_buckets(s, tl, q, model), tl, s.emission.mode);
}

// A quad light (an area light: a point on it per segment, then the distance) above the haze
// the camera looks into, against a quadrature.
TEST(SingleScatter, QuadLightInTheHaze) {
    SceneDesc s = quad_in_haze();
    const auto want = quad_reference(s);
    // Frames with at least 5% of the brightest one's light: the onset frame, where the light
    // first reaches a few pixels' rays, depends on where in the pixel the rays run (the
    // quadrature's 2 x 2 rays, the render's jittered ones).
    // The light's point, drawn once per segment, is shared by the segment's frames: the image's
    // mean is noisier than with a point light (seeds 1-3 at 64 passes: +0.2%, +0.2%, -0.5%).
    s.render.passes = 64;
    const FrameErrors e = compare(test::render_all(s), want, 0.05);
    print("quad light", e);
    ASSERT_GE(e.mean_dev.size(), 8u);
    EXPECT_LT(std::abs(e.mean_dev[0]), 0.05);  // the onset: as for the spot
    for (size_t k = 1; k < e.mean_dev.size(); ++k) EXPECT_LT(std::abs(e.mean_dev[k]), 0.015) << "lit frame " << k;
}

// The same quad flashing for one frame (0.5 ns, 15 cm of light: a ninth of the quad's 1.3 m
// diagonal). Each frame then holds one bucket, and a distance sample whose light comes from a
// fresh point of the quad (by solid angle) arrives at a time of its own, up to three buckets
// from its stratum's; one point of the quad's area per segment keeps every sample in its
// frame. Both are unbiased (each lit frame's mean against the quadrature: the solid angle's
// within its noise, +-3.4% at 32 passes, the area point's within 1.1%); the area point's frames
// must also be the less noisy (per-pixel error against the quadrature, seeds 1-3: measured
// 0.124 by solid angle, 0.024 by area point).
TEST(SingleScatter, FlashingQuadLightEveryFrameInItsBucket) {
    SceneDesc s = quad_in_haze();
    s.emission.mode = EmissionMode::Pulse;
    s.emission.width_frames = 1;
    s.time = {0, 20, 40, 24};
    const auto want = quad_reference(s);
    s.render.passes = 32;
    double rel[2] = {0, 0};
    for (int by_area = 0; by_area < 2; ++by_area)
        for (uint64_t seed = 1; seed <= 3; ++seed) {
            s.render.seed = seed;
            const test::Rendered r =
                test::render_switched(s, [by_area](RenderContext& ctx) { ctx.pulse_quads_by_area = by_area == 1; });
            const FrameErrors e = compare(r, want, 0.05);
            std::printf("flashing quad, %s, seed %d: ", by_area ? "area point" : "solid angle", int(seed));
            print("", e);
            ASSERT_GE(e.mean_dev.size(), 6u);
            for (size_t k = 0; k < e.mean_dev.size(); ++k)
                EXPECT_LT(std::abs(e.mean_dev[k]), by_area ? 0.02 : 0.06)
                    << (by_area ? "area point" : "solid angle") << ", lit frame " << k;
            // Light where the quadrature's 2 x 2 rays a pixel have none: the onset's edges only.
            EXPECT_LT(e.dark, 0.005);
            rel[by_area] += e.pixel_rel / 3;
        }
    std::printf("per-pixel error: solid angle %.4f, area point %.4f\n", rel[0], rel[1]);
    EXPECT_LT(rel[1], 0.8 * rel[0]) << "one area point a segment: every sample in its own frame";
}

// An emissive mesh in the fog (two triangles, emitting from both faces; sampled by power over
// its triangles, then the distance), above and behind the camera, against the same quadrature.
TEST(SingleScatter, EmissiveMeshInTheHaze) {
    SceneDesc s = test::light_in_open_medium(test::point_light({0, 0, 0}, 1), Vec3(0.05f), Vec3(0.3f), 0.2f, 5, {0, 0, -2},
                                             {0, 0, 1}, 50, 12);
    s.lights.clear();
    MaterialDesc glow;
    glow.name = "glow";
    glow.emission = Vec3(20, 12, 6);
    glow.double_sided = true;
    s.materials.push_back(glow);
    auto mesh = std::make_shared<MeshData>();
    const Vec3 c0{-0.4f, 1.8f, -3.4f}, e1{0.8f, 0, 0}, e2{0, 0, 0.7f};
    mesh->positions = {c0, c0 + e1, c0 + e1 + e2, c0 + e2};
    mesh->indices = {0, 1, 2, 0, 2, 3};
    mesh->tri_material = {1, 1};
    ShapeDesc shape;
    shape.type = ShapeType::Mesh;
    shape.material = 1;
    shape.mesh = mesh;
    s.shapes.push_back(shape);
    s.time = {0, 30, 12, 24};
    s.render.photons_per_pass = 2000;
    s.render.passes = 64;
    const Timeline tl = timeline_of(s);
    test::QuadratureSetup q = test::quadrature_setup(s);
    q.steps = 1500;
    const int n = 8;
    const Vec3 normal = normalize(cross(e1, e2));
    const float piece = length(cross(e1, e2)) / (n * n);
    test::LightModel model = [&](Vec3 x, const std::function<void(const test::LightContribution&)>& add) {
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b) {
                const Vec3 at = c0 + e1 * ((a + 0.5f) / n) + e2 * ((b + 0.5f) / n);
                test::point_model(at, [&](Vec3 w) { return glow.emission * (piece * std::abs(dot(w, normal))); })(x, add);
            }
    };
    const auto want = test::frames_of(test::single_scatter_buckets(s, tl, q, model), tl, s.emission.mode);
    const FrameErrors e = compare(test::render_all(s), want, 0.05);
    print("emissive mesh", e);
    ASSERT_GE(e.mean_dev.size(), 8u);
    EXPECT_LT(std::abs(e.mean_dev[0]), 0.05);  // the onset: as for the spot
    for (size_t k = 1; k < e.mean_dev.size(); ++k) EXPECT_LT(std::abs(e.mean_dev[k]), 0.015) << "lit frame " << k;
}

// A sun at a grazing angle (3 degrees above the horizon) through a haze slab, g = 0 (so the
// sun's half-degree disc does not matter to the quadrature, which takes it as collimated).
TEST(SingleScatter, GrazingSunInAHazeSlab) {
    LightDesc sun;
    sun.type = LightType::Sun;
    sun.direction = normalize(Vec3(1, -std::tan(3 * kPi / 180), 0.2f));
    sun.irradiance = Vec3(50);
    SceneDesc s = test::light_in_open_medium(sun, Vec3(0.02f, 0.05f, 0.0f), Vec3(0.2f, 0.2f, 0.1f), 0.0f, 5,
                                             {0, 0, -3}, {0, 0.5f, 1}, 60, 12);
    s.medium.bounds_min = {-5, -2, -5};
    s.medium.bounds_max = {5, 2, 5};
    s.time = {0, 40, 16, 24};
    s.render.photons_per_pass = 2000;
    s.render.passes = 16;
    const Timeline tl = timeline_of(s);
    test::QuadratureSetup q = test::quadrature_setup(s);
    const Vec3 D = normalize(sun.direction);
    // The wavefront enters the scene's bounds (here the medium's box) at t = 0.
    double h0 = 1e30;
    for (int c = 0; c < 8; ++c) {
        const Vec3 p{(c & 1) ? q.hi.x : q.lo.x, (c & 2) ? q.hi.y : q.lo.y, (c & 4) ? q.hi.z : q.lo.z};
        h0 = std::min(h0, static_cast<double>(dot(p, D)));
    }
    test::LightModel model = [&](Vec3 x, const std::function<void(const test::LightContribution&)>& add) {
        add({sun.irradiance, -D, (dot(x, D) - h0) / test::kC, test::box_exit(x, -D, q.lo, q.hi)});
    };
    const auto want = test::frames_of(test::single_scatter_buckets(s, tl, q, model), tl, s.emission.mode);
    const FrameErrors e = compare(test::render_all(s), want, 0.05);  // (the onset frame: as for the quad)
    print("grazing sun", e);
    EXPECT_LT(worst(e.mean_dev), 0.015);
    EXPECT_LT(e.dark, 1e-4);
}

// The sun through a window: an opaque black ceiling at y = 2.5 across the haze box with a 2 m x
// 2 m opening, the sun above it (60 degrees up); the camera below looks across the shaft of
// light the window casts into the haze (its rays stay below the ceiling). The quadrature lights
// a point when the way to the sun crosses the ceiling's plane inside the opening; g = 0 and
// a sun of 0.01 degrees, so that the penumbra does not matter.
struct SunWindow {
    SceneDesc scene;
    std::vector<std::vector<Vec3>> want;  // the quadrature's frames
};
SunWindow sun_through_a_window() {
    LightDesc sun;
    sun.type = LightType::Sun;
    sun.direction = normalize(Vec3(0.3f, -1.0f, 0.5f));
    sun.irradiance = Vec3(200);
    sun.angle_deg = 0.01f;
    SceneDesc s = test::light_in_open_medium(sun, Vec3(0.02f), Vec3(0.3f, 0.2f, 0.1f), 0.0f, 5, {0, -1.5f, -3},
                                             {0.5f, -1.5f, 1}, 40, 16);
    const float ceiling = 2.5f, wx0 = -1.0f, wx1 = 1.0f, wz0 = -0.5f, wz1 = 1.5f;
    auto quad = [&](float x0, float x1, float z0, float z1) {
        ShapeDesc q;
        q.type = ShapeType::Quad;
        q.material = 0;  // black
        q.corner = {x0, ceiling, z0};
        q.edge1 = {x1 - x0, 0, 0};
        q.edge2 = {0, 0, z1 - z0};
        s.shapes.push_back(q);
    };
    quad(-5, 5, -5, wz0);    // in front of the opening
    quad(-5, 5, wz1, 5);     // behind it
    quad(-5, wx0, wz0, wz1);  // left of it
    quad(wx1, 5, wz0, wz1);   // right of it
    s.time = {0, 40, 16, 24};
    s.render.photons_per_pass = 2000;
    const Timeline tl = timeline_of(s);
    test::QuadratureSetup q = test::quadrature_setup(s);
    q.sub = 4;  // the shaft's edges cross pixels
    const Vec3 D = normalize(sun.direction);
    double h0 = 1e30;  // the wavefront enters the scene's bounds (the medium's box) at t = 0
    for (int c = 0; c < 8; ++c) {
        const Vec3 p{(c & 1) ? q.hi.x : q.lo.x, (c & 2) ? q.hi.y : q.lo.y, (c & 4) ? q.hi.z : q.lo.z};
        h0 = std::min(h0, static_cast<double>(dot(p, D)));
    }
    test::LightModel model = [&](Vec3 x, const std::function<void(const test::LightContribution&)>& add) {
        if (x.y < ceiling) {  // below the ceiling: lit through the opening only
            const float t = (ceiling - x.y) / -D.y;
            const Vec3 at = x - D * t;
            if (!(at.x > wx0 && at.x < wx1 && at.z > wz0 && at.z < wz1)) return;
        }
        add({sun.irradiance, -D, (dot(x, D) - h0) / test::kC, test::box_exit(x, -D, q.lo, q.hi)});
    };
    // Every camera ray must stay below the ceiling up to the box's far side.
    PinholeCamera cam(s.camera);
    for (int c = 0; c < 4; ++c) {
        const Vec3 d = cam.direction((c & 1) ? 16.0f : 0.0f, (c & 2) ? 16.0f : 0.0f);
        const Vec3 end = cam.position() + d * static_cast<float>(test::box_exit(cam.position(), d, q.lo, q.hi));
        EXPECT_LT(end.y, ceiling);
    }
    return {s, test::frames_of(test::single_scatter_buckets(s, tl, q, model), tl, s.emission.mode)};
}

TEST(SingleScatter, SunThroughAWindow) {
    SunWindow w = sun_through_a_window();
    // Most distance samples fall outside the shaft: at 64 passes the frames' means are still
    // +-1.5% from seed to seed; at 256 within 0.5%.
    w.scene.render.passes = 256;
    const FrameErrors e = compare(test::render_all(w.scene), w.want, 0.05);  // (the onset frame: as for the quad)
    print("sun through a window", e);
    ASSERT_GE(e.mean_dev.size(), 4u);
    EXPECT_LT(std::abs(e.mean_dev[0]), 0.05);  // the onset
    for (size_t k = 1; k < e.mean_dev.size(); ++k) EXPECT_LT(std::abs(e.mean_dev[k]), 0.01) << "lit frame " << k;
    EXPECT_LT(e.dark, 1e-3);
}

// The same shaft at 64 passes, the light sample and the distances' uniform of each pixel's
// first segment stratified over the passes (what the program does) or drawn at random: each
// distance sample is lit or not, so stratified the per-pixel error against the quadrature must
// fall faster, with the frames' means unchanged (seeds 1-3; measured: 0.103 independent, 0.052
// stratified).
TEST(SingleScatter, AShaftConvergesFasterWithSamplesStratifiedOverPasses) {
    SunWindow w = sun_through_a_window();
    w.scene.render.passes = 64;
    double rel[2] = {0, 0};
    for (int stratified = 0; stratified < 2; ++stratified)
        for (uint64_t seed = 1; seed <= 3; ++seed) {
            w.scene.render.seed = seed;
            const test::Rendered r = test::render_switched(
                w.scene, [stratified](RenderContext& ctx) { ctx.stratified_light_points = stratified == 1; });
            const FrameErrors e = compare(r, w.want, 0.05);
            std::printf("shaft, %s, seed %d: ", stratified ? "stratified" : "independent", int(seed));
            print("", e);
            ASSERT_GE(e.mean_dev.size(), 4u);
            // (after the onset; independent samples' means spread by up to 3.6% at 64 passes)
            for (size_t k = 1; k < e.mean_dev.size(); ++k)
                EXPECT_LT(std::abs(e.mean_dev[k]), stratified ? 0.02 : 0.05) << "lit frame " << k;
            rel[stratified] += e.pixel_rel / 3;
        }
    std::printf("per-pixel error: independent %.4f, stratified %.4f\n", rel[0], rel[1]);
    EXPECT_LT(rel[1], 0.8 * rel[0]) << "stratified over the passes: a shaft's lit share converges faster";
}

// Haze seen through mirrors: two parallel mirrors z = +-1.5 and the camera between them looking
// at a slant, max_depth 3: every camera path crosses the medium three times (the third piece was
// dropped when at most two gathered). A narrow spot along x lights the haze between the mirrors
// without reaching them, so no light reaches the haze by a mirror.
TEST(SingleScatter, SegmentsAfterSpecularBouncesGather) {
    LightDesc spot;
    spot.type = LightType::Spot;
    spot.position = {4.5f, 0, 0};
    spot.direction = {-1, 0, 0};
    spot.cone_deg = 7;  // the half-angle: 1.2 m from the axis at the box's far side
    spot.power = Vec3(50);
    SceneDesc s = test::light_in_open_medium(spot, Vec3(0.01f), Vec3(0.01f), 0.0f, 5, {-2, 0, -1.4f},
                                             {-1.2f, 0, 0.0f}, 40, 12);
    MaterialDesc mirror;
    mirror.name = "mirror";
    mirror.type = MaterialType::Mirror;
    s.materials.push_back(mirror);
    for (float z : {1.5f, -1.5f}) {
        ShapeDesc q;
        q.type = ShapeType::Quad;
        q.material = 1;
        q.corner = {-5, -5, z};
        q.edge1 = {10, 0, 0};
        q.edge2 = {0, 10, 0};
        s.shapes.push_back(q);
    }
    s.render.max_depth = 3;
    s.time = {0, 40, 8, 24};
    s.render.photons_per_pass = 2000;
    // 128 passes: at 16 the frames' means moved by +-4 % from seed to seed (seeds 1-8: -2 % to
    // +7 %), wider than what is checked; at 128, +1.3 % to +3.9 % (seeds 1-6).
    s.render.passes = 128;
    const Timeline tl = timeline_of(s);
    test::QuadratureSetup q = test::quadrature_setup(s);
    q.mirror_z = {1.5f, -1.5f};
    const double cos_cone = std::cos(7 * kPiDouble / 180);
    const float I = static_cast<float>(50 / (2 * kPiDouble * (1 - cos_cone)));
    const auto model = test::point_model(spot.position, [=](Vec3 w) { return -w.x >= cos_cone ? Vec3(I) : Vec3(0); });
    q.max_segments = 2;
    const auto two = test::frames_of(test::single_scatter_buckets(s, tl, q, model), tl, s.emission.mode);
    q.max_segments = 3;
    const auto want = test::frames_of(test::single_scatter_buckets(s, tl, q, model), tl, s.emission.mode);
    double w2 = 0, w3 = 0;
    for (size_t p = 0; p < want.size(); ++p) {
        w2 += average(two[p].back());
        w3 += average(want[p].back());
    }
    std::printf("mirrors: the third piece holds %.1f%% of the last frame\n", 100 * (1 - w2 / w3));
    ASSERT_GT(1 - w2 / w3, 0.05) << "the scene must make the third piece matter";
    const test::Rendered r = test::render_all(s);
    const FrameErrors e = compare(r, want, 0.2);
    print("mirrors", e);
    // Multiple scattering (photons; light scattered out of the beam is trapped between the
    // mirrors) adds a little on top, sigma_s being 0.01 /m; without the third piece the frames
    // would fall short by its share.
    // The first lit frame is the onset near the spot (as in SpotAimedAtTheCamera): left out.
    ASSERT_GE(e.mean_dev.size(), 4u);
    for (size_t k = 1; k < e.mean_dev.size(); ++k) {
        EXPECT_GT(e.mean_dev[k], -0.015) << "lit frame " << k;
        EXPECT_LT(e.mean_dev[k], 0.05) << "lit frame " << k;
    }
}

// Energy: next-event estimation of single scattering plus the volume photons of depth >= 2
// must equal the photons alone (which carried every order before), with multiple scattering
// (max_depth 3) and a white floor the light scatters off into the haze. The camera looks at the
// haze from outside the box, where the photon estimate is quiet; single scattering is about
// half of the image, so counting it twice (or dropping it) would be off by tens of percent.
TEST(SingleScatter, NextEventPlusPhotonsEqualsPhotonsAlone) {
    SceneDesc s = test::light_in_open_medium(test::point_light({0, 1.2f, 0.5f}, 200), Vec3(0.05f), Vec3(0.35f), 0.3f, 1.5f,
                                             {0, 0.3f, -5}, {0, -0.8f, 0}, 30, 24);
    MaterialDesc white;
    white.name = "white";
    white.albedo = Vec3(0.7f);
    s.materials.push_back(white);
    ShapeDesc floor;
    floor.type = ShapeType::Quad;
    floor.material = 1;
    floor.corner = {-1.5f, -1.5f, -1.5f};
    floor.edge1 = {0, 0, 3};
    floor.edge2 = {3, 0, 0};
    s.shapes.push_back(floor);
    s.render.max_depth = 3;
    s.time = {0, 40, 8, 24};
    s.render.photons_per_pass = 50000;
    s.render.passes = 24;
    s.render.radius = 0.05f;
    const test::Rendered nee = render_mode(s, false), photons = render_mode(s, true);
    SceneDesc single = s;
    single.render.max_depth = 1;
    const double m_nee = test::mean(nee.steady), m_ph = test::mean(photons.steady);
    const double m_single = test::mean(render_mode(single, false).steady);
    std::printf("steady mean: next-event + photons %.6g, photons alone %.6g (%+.4f); single scattering %.1f%%\n",
                m_nee, m_ph, m_nee / m_ph - 1, 100 * m_single / m_nee);
    ASSERT_GT(m_single / m_nee, 0.2);
    EXPECT_NEAR(m_nee / m_ph, 1.0, 0.03);
    for (size_t k = 0; k < nee.frames.size(); ++k) {
        const double a = test::mean(nee.frames[k]), b = test::mean(photons.frames[k]);
        if (b > 0.05 * m_ph) {
            EXPECT_NEAR(a / b, 1.0, 0.05) << "frame " << k;
        }
    }
}

// A laser's beam is a delta direction no camera ray meets: its single scattering stays with the
// photons, and the image is the same, bit for bit, with either estimator.
TEST(SingleScatter, LaserKeepsItsSingleScatteringPhotons) {
    LightDesc laser;
    laser.type = LightType::Laser;
    laser.position = {-4, 0, 0};
    laser.direction = {1, 0, 0};
    laser.power = Vec3(5);
    laser.radius = 0.01f;
    SceneDesc s = test::light_in_open_medium(laser, Vec3(0.02f), Vec3(0.2f), 0.0f, 5, {0, 0, -4}, {0, 0, 0}, 50, 16);
    s.time = {0, 40, 8, 24};
    s.render.photons_per_pass = 5000;
    s.render.passes = 4;
    const test::Rendered a = render_mode(s, false), b = render_mode(s, true);
    EXPECT_GT(test::mean(a.steady), 0);
    EXPECT_EQ(a.steady, b.steady);
}

}  // namespace
}  // namespace sl
