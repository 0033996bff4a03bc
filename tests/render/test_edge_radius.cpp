// Gather radii that stop short of a surface's edges (edge_radius.h). A grey plate floats in
// nothing, lit straight down by a laser beam wider than it (every arrival is a stored photon:
// the plate's light comes through the gather alone), so its radiance is rho E / pi everywhere
// on it, E = P / (pi a^2) from the beam's flux and cross-section. A gather disc that reaches past
// the plate's edge finds nothing there: with one radius of three pixel footprints for every pixel,
// the plate's outermost pixels come out about a third too dark.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "pipeline/frames_in_memory.h"
#include "pipeline/render_frames.h"
#include "render_helpers.h"
#include "scenes_for_tests.h"
#include "stages/render/edge_radius.h"

namespace sl {
namespace {

constexpr int kRes = 40;           // the camera sees +-0.4 m: 2 cm a pixel
constexpr float kHalf = 0.2f;      // the plate: 0.4 m square, pixels 10..29 each way
constexpr float kBeam = 0.5f, kPower = 1, kRho = 0.5f;
constexpr double kPi = 3.14159265358979;

SceneDesc plate_in_a_beam() {
    SceneDesc s = test::looking_down_at_grey("<test plate in a beam>", kRes, 0.4f, kRho);
    MaterialDesc black;
    black.name = "black";
    black.albedo = Vec3(0);
    s.materials.push_back(black);
    s.shapes.push_back(test::quad({-kHalf, 0, kHalf}, {2 * kHalf, 0, 0}, {0, 0, -2 * kHalf}));
    s.shapes.push_back(test::quad({-2, -1, 2}, {4, 0, 0}, {0, 0, -4}, 1));  // the floor, far below the plate
    s.lights.push_back(test::laser({0, 1, 0}, {0, -1, 0}, kBeam, kPower));
    s.time = {0, 100, 2, 24};
    s.render.passes = 16;
    s.render.photons_per_pass = 100000;
    s.render.max_depth = 1;
    return s;
}

// Mean of the first channel over the pixels (x, y) with x in [x0, x1), y in [y0, y1).
double box(const test::Rendered& r, int x0, int x1, int y0, int y1) {
    double sum = 0;
    int n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x, ++n) sum += r.steady[(static_cast<size_t>(y) * kRes + x) * 3];
    return sum / n;
}

// The plate's outermost ring of pixels but its corners, and its middle.
struct PlateBands {
    double edge, middle;
};
PlateBands bands(const test::Rendered& r) {
    const double edge = (box(r, 10, 11, 12, 28) + box(r, 29, 30, 12, 28) + box(r, 12, 28, 10, 11) + box(r, 12, 28, 29, 30)) / 4;
    return {edge, box(r, 15, 25, 15, 25)};
}

const double kWant = kRho / kPi * kPower / (kPi * kBeam * kBeam);

TEST(EdgeRadius, ThePlatesOutermostPixelsAreAsBrightAsItsMiddle) {
    const PlateBands b = bands(test::render_all(plate_in_a_beam()));
    std::printf("analytic %.4f; middle %.4f (%.4fx), outermost pixels %.4f (%.4fx)\n", kWant, b.middle,
                b.middle / kWant, b.edge, b.edge / kWant);
    EXPECT_NEAR(b.middle, kWant, 0.03 * kWant);
    // The outermost pixels' discs are cut at the plate's edge (found to 1/64 of a pixel), so
    // they lose nothing beyond it. Measured: 1.001 (with discs shrunk to the edge's distance
    // instead, whose points past the pixel's centre still reach over the edge: 0.927; one
    // radius for all: 0.64, the next test).
    EXPECT_GT(b.edge, 0.97 * kWant);
    EXPECT_LT(b.edge, 1.02 * kWant);
}

// A set of the plate's pixels over seeds, rendered with or without the edge cuts (each pixel
// beside an edge then gathers in the disc shrunk to the edge's distance) and with or without
// stars (their pixels then gather as if they had none).
struct Band {
    double mean = 0;     // over the pixels and the seeds, in units of the analytic radiance
    double spread = 0;   // per pixel: the RMS over the pixels of each one's standard deviation over seeds
};
// The pixels of `scene` (with `set` applied to its context) over seeds, in units of `want`.
Band band_of(SceneDesc (*scene)(), const std::function<void(RenderContext&)>& set,
             const std::vector<std::pair<int, int>>& pixels, int seeds, double want) {
    std::vector<double> m(pixels.size(), 0.0), m2(pixels.size(), 0.0);
    for (int seed = 1; seed <= seeds; ++seed) {
        SceneDesc s = scene();
        s.render.seed = static_cast<uint64_t>(seed);
        RenderContext ctx(s);
        set(ctx);
        FramesInMemory sink;
        render_frames(ctx, {Strategy::Single, 1}, sink);
        for (size_t i = 0; i < pixels.size(); ++i) {
            const auto [x, y] = pixels[i];
            const double v = sink.steady[(static_cast<size_t>(y) * kRes + x) * 3] / want;
            m[i] += v, m2[i] += v * v;
        }
    }
    Band b;
    double var = 0;
    for (size_t i = 0; i < pixels.size(); ++i) {
        const double mean = m[i] / seeds;
        b.mean += mean;
        var += (m2[i] - seeds * mean * mean) / (seeds - 1);
    }
    b.mean /= static_cast<double>(pixels.size());
    b.spread = std::sqrt(var / static_cast<double>(pixels.size()));
    return b;
}
Band band_over(const std::vector<std::pair<int, int>>& pixels, int seeds, bool cuts, bool stars) {
    return band_of(
        plate_in_a_beam,
        [&](RenderContext& ctx) {
            ctx.edge_cuts = cuts;
            ctx.edge_stars = stars;
        },
        pixels, seeds, kWant);
}

// `after` has the analytic light, `before` less (the shrunk discs reach a little over the
// edges), and `after` is less noisy than `ratio` times `before`.
void expect_lighter_and_less_noisy(const char* what, const Band& before, const Band& after, double ratio) {
    std::printf("%s, 6 seeds: before mean %.4f spread %.4f; after mean %.4f spread %.4f (%.2fx less)\n", what,
                before.mean, before.spread, after.mean, after.spread, before.spread / after.spread);
    EXPECT_NEAR(after.mean, 1.0, 0.015);
    EXPECT_LT(before.mean, after.mean);
    EXPECT_LT(after.spread, ratio * before.spread);
}

// The plate's edge band: its two outermost rings of pixels.
std::vector<std::pair<int, int>> edge_band() {
    std::vector<std::pair<int, int>> pixels;
    for (int y = 10; y < 30; ++y)
        for (int x = 10; x < 30; ++x)
            if (!(x >= 12 && x < 28 && y >= 12 && y < 28)) pixels.push_back({x, y});
    return pixels;
}

TEST(EdgeRadius, CutDiscsMakeTheEdgeBandLessNoisyAndNoDarker) {
    // Beside an edge the shrunk disc holds a fraction of its neighbours' photons, and its
    // points past the pixel's edge still lose the part beyond it: the band is the noisiest part
    // of the plate, and a little dark. Cut at the edge's line, the disc keeps its size and
    // nothing beyond the edge: the analytic light, from several times the photons (the corners
    // keep stars: the next test). Measured (6 seeds): shrunk 0.957, spread 0.0248; cut 1.000,
    // spread 0.0050 (0.996 and 0.0081 before the corners' stars).
    expect_lighter_and_less_noisy("edge band, shrunk discs before, cut after", band_over(edge_band(), 6, false, true),
                                  band_over(edge_band(), 6, true, true), 0.5);
}

// The plate's four corners: the 3 x 3 pixels at each.
std::vector<std::pair<int, int>> corners() {
    std::vector<std::pair<int, int>> pixels;
    for (const int x0 : {10, 27})
        for (const int y0 : {10, 27})
            for (int y = y0; y < y0 + 3; ++y)
                for (int x = x0; x < x0 + 3; ++x) pixels.push_back({x, y});
    return pixels;
}

TEST(EdgeRadius, ThePlatesCornersKeepStarsOnThePlate) {
    // At a corner no one line accounts for the two edges: the cut takes one, the other caps the
    // radius. The corner's diagonal pixels keep a star instead: the disc, sector by sector, up
    // to where the plate ends, found ray by ray.
    const RenderContext ctx(plate_in_a_beam());
    const GatherRadii& radii = ctx.gather_radii();
    for (const int x0 : {10, 29})
        for (const int y0 : {10, 29})
            for (int k = 0; k < 3; ++k) {
                const int x = x0 == 10 ? x0 + k : x0 - k, y = y0 == 10 ? y0 + k : y0 - k;
                SCOPED_TRACE(::testing::Message() << "pixel " << x << ", " << y);
                const EdgeStar* st = radii.star(static_cast<size_t>(y) * kRes + x);
                ASSERT_NE(st, nullptr);
                // Each sector's farthest points (its two rays and its middle) stay on the plate.
                Vec3 t, b;
                make_basis(decode_normal(st->normal), t, b);
                for (int s = 0; s < EdgeStar::kSectors; ++s)
                    for (const float a : {0.0f, 0.5f, 1.0f}) {
                        const float ang = (s + a) * 2 * 3.14159265f / EdgeStar::kSectors - 3.14159265f;
                        const Vec3 far = st->centre + (t * std::cos(ang) + b * std::sin(ang)) * st->reach_of(s);
                        EXPECT_LT(std::max(std::abs(far.x), std::abs(far.z)), kHalf + 1e-4f) << "sector " << s;
                    }
            }
    // Measured (6 seeds): without 0.971, spread 0.0128; with 0.9992, spread 0.0086.
    expect_lighter_and_less_noisy("corners, without stars before, with after", band_over(corners(), 6, true, false),
                                  band_over(corners(), 6, true, true), 0.75);
}

// A plate over a floor of the same grey, both in one laser beam wide enough to light the floor
// round the plate's shadow (the floor far below, so that what the camera sees of it beside the
// plate is lit): every pixel in view has the same radiance, rho E / pi, whichever surface its
// points see. The plate's edges fall a quarter of a pixel inside its outermost pixels: their
// centres see the plate (they have cuts), a quarter of their points the floor.
constexpr float kWideBeam = 1.0f;
constexpr float kOffHalf = 0.215f;  // plate edges at image x, y = 9.25 and 30.75
SceneDesc plate_over_a_lit_floor() {
    SceneDesc s = plate_in_a_beam();
    s.shapes.clear();
    s.shapes.push_back(test::quad({-kOffHalf, 0, kOffHalf}, {2 * kOffHalf, 0, 0}, {0, 0, -2 * kOffHalf}));
    s.shapes.push_back(test::quad({-2, -3, 2}, {4, 0, 0}, {0, 0, -4}));  // grey, as the plate
    s.lights = {test::laser({0, 1, 0}, {0, -1, 0}, kWideBeam, kPower)};
    return s;
}

// The plate's outermost pixels along its four sides (not its corners), over seeds, in units of
// the analytic radiance, with or without neighbours' discs for the points off the plate.
Band silhouette_over(int seeds, bool neighbours) {
    const double want = kRho / kPi * kPower / (kPi * kWideBeam * kWideBeam);
    std::vector<std::pair<int, int>> pixels;
    for (int k = 12; k < 28; ++k) {
        pixels.push_back({9, k});
        pixels.push_back({30, k});
        pixels.push_back({k, 9});
        pixels.push_back({k, 30});
    }
    return band_of(plate_over_a_lit_floor, [&](RenderContext& ctx) { ctx.edge_neighbours = neighbours; }, pixels,
                   seeds, want);
}

TEST(EdgeRadius, PointsAcrossASilhouetteGatherAsTheNeighbourThatSeesTheirSurface) {
    // The plate's outermost pixels have cuts; their points on the floor used to gather in the
    // disc shrunk to the plate's edge (a quarter of a pixel: a photon or none, a firefly or a
    // hole). The floor goes on under the plate's silhouette, so they now gather as the floor
    // pixel beside them does, in its whole disc.
    {
        const RenderContext ctx(plate_over_a_lit_floor());
        const GatherRadii& radii = ctx.gather_radii();
        ASSERT_NE(radii.cut(static_cast<size_t>(20) * kRes + 9), nullptr);
        ASSERT_EQ(radii.plane.size(), static_cast<size_t>(kRes * kRes));
        // A point on the floor seen through pixel (9, 20): its neighbour (8, 20) sees the floor.
        const Vec3 eye = ctx.camera.position(), d = ctx.camera.direction(9.1f, 20.5f);
        const Vec3 x = eye + d * ((eye.y + 3) / -d.y);
        EXPECT_EQ(radii.neighbour_on(static_cast<size_t>(20) * kRes + 9, kRes, x, {0, 1, 0}, 0.01f), 20 * kRes + 8);
        EXPECT_EQ(radii.neighbour_on(static_cast<size_t>(20) * kRes + 9, kRes, x, {1, 0, 0}, 0.01f), -1);
    }
    // Measured (6 seeds): shrunk discs 0.9995, spread 0.0355; neighbours' discs 1.0009, spread
    // 0.0104. (Before every edge pixel in reach was bisected, the cut stood at these pixels'
    // centres, a quarter of a pixel short of the edge: 0.951 and 0.977.)
    const Band before = silhouette_over(6, false), after = silhouette_over(6, true);
    std::printf("silhouette, 6 seeds: shrunk discs mean %.4f spread %.4f; neighbours' mean %.4f spread %.4f (%.2fx less)\n",
                before.mean, before.spread, after.mean, after.spread, before.spread / after.spread);
    EXPECT_NEAR(after.mean, 1.0, 0.015);
    EXPECT_LT(after.spread, 0.5 * before.spread);
}

TEST(EdgeRadius, TheFootOfAWallIsNoEdgeOfTheFloor) {
    // A floor and a wall rising from it, seen at a slant: a pixel beside the foot may see the
    // wall within a tenth of the radius of the floor's plane, turned up from it. That is a wall
    // rising (a concave corner, which the gather's blockers cut), not the floor's end: the floor
    // pixels round the foot keep the whole radius, no cut and no star (the cathedral's floor
    // along its walls had stars, which fell back to the shrunk disc beside the wall). The wall
    // stands at 8 offsets a fraction of a pixel apart, so some pixel's centre sees its foot.
    for (int k = 0; k < 8; ++k) {
        SCOPED_TRACE(::testing::Message() << "offset " << k);
        SceneDesc s;
        s.source = "<test floor and wall>";
        s.camera.position = {0, 1.0f, 1.5f};
        s.camera.look_at = {0, 0, -0.3f};
        s.camera.up = {0, 1, 0};
        s.camera.vfov_deg = 40;
        s.camera.width = s.camera.height = kRes;
        MaterialDesc grey;
        grey.name = "grey";
        grey.albedo = Vec3(0.5f);
        s.materials.push_back(grey);
        const float zw = -0.3f - 0.004f * k;
        s.shapes.push_back(test::quad({-1, 0, 1}, {2, 0, 0}, {0, 0, zw - 1}));  // the floor, up to the wall
        s.shapes.push_back(test::quad({-1, 0, zw}, {2, 0, 0}, {0, 1, 0}));      // the wall
        s.lights.push_back(test::laser({0, 1, 0}, {0, -1, 0}, 0.5f, 1));
        s.time = {0, 100, 2, 24};
        s.render.passes = 1;
        s.render.photons_per_pass = 1000;
        s.render.max_depth = 1;
        const RenderContext ctx(s);
        const GatherRadii& radii = ctx.gather_radii();
        ASSERT_EQ(radii.radius.size(), static_cast<size_t>(kRes * kRes));
        int checked = 0;
        for (int y = 1; y + 1 < kRes; ++y)
            for (int x = 2; x + 2 < kRes; ++x) {
                SurfaceHit h;
                const Vec3 eye = ctx.camera.position();
                if (!ctx.geometry.intersect(eye, ctx.camera.direction(x + 0.5f, y + 0.5f), 0, 1e30f, h)) continue;
                if (!(h.normal.y > 0.9f || h.normal.y < -0.9f)) continue;  // a floor pixel
                bool by_wall = false;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        SurfaceHit q;
                        if (ctx.geometry.intersect(eye, ctx.camera.direction(x + dx + 0.5f, y + dy + 0.5f), 0, 1e30f, q) &&
                            std::abs(q.normal.y) < 0.1f)
                            by_wall = true;
                    }
                if (!by_wall) continue;
                const size_t i = static_cast<size_t>(y) * kRes + x;
                ++checked;
                EXPECT_FLOAT_EQ(radii.radius[i], ctx.initial_radius) << "pixel " << x << ", " << y;
                EXPECT_EQ(radii.cut(i), nullptr) << "pixel " << x << ", " << y;
                EXPECT_EQ(radii.star(i), nullptr) << "pixel " << x << ", " << y;
            }
        EXPECT_GT(checked, 20);
    }
}

TEST(EdgeRadius, OneRadiusForEveryPixelLeavesTheEdgesDark) {
    // The same scene at the automatic radius given as the scene's own: every pixel starts at it.
    SceneDesc s = plate_in_a_beam();
    s.render.radius = RenderContext(s).initial_radius;
    const PlateBands b = bands(test::render_all(s));
    std::printf("radius %.4f m for all: middle %.4fx, outermost pixels %.4fx\n", s.render.radius, b.middle / kWant,
                b.edge / kWant);
    EXPECT_NEAR(b.middle, kWant, 0.03 * kWant);
    EXPECT_LT(b.edge, 0.8 * kWant);
}

TEST(EdgeRadius, DiscsAreCutAtAnEdgeAndNotAtAWallOrAnOccluder) {
    // The plate, and a wall rising from its far half (x > 0.1): the plate's near part meets the
    // wall in a concave corner (the gather's blockers cut the disc there), not an edge.
    SceneDesc s = plate_in_a_beam();
    s.shapes.push_back(test::quad({0.1f, 0, kHalf}, {0, 0, -2 * kHalf}, {0, 0.3f, 0}));
    const RenderContext ctx(s);
    const float r0 = ctx.initial_radius, step = 0.02f;  // the plate's pixel, in metres
    ASSERT_EQ(ctx.gather_radii().radius.size(), static_cast<size_t>(kRes * kRes));
    auto radius = [&](int x, int y) { return ctx.gather_radii().radius[static_cast<size_t>(y) * kRes + x]; };
    EXPECT_GT(r0, 3 * step);  // three pixel footprints at the scene's middle, under the plate
    // Which way image x runs on the plate: the wall stands at x = 0.1, 5 pixels from the middle.
    const Vec3 d = ctx.camera.direction(35.5f, 20.5f);
    const bool x_runs_along = d.x > 0;
    const int free_side = x_runs_along ? 10 : 29;
    const int inward = x_runs_along ? 1 : -1;
    // The free edge: 1, 2 pixels in, the disc keeps r0 and is cut at a line along the edge, at
    // the edge itself (found by bisection between the pixels' rays): half a step out from the
    // outermost pixel's centre, 1.5 steps from the next one's. A point of the pixel past the
    // line (or off the plate) gathers in the shrunk disc: at most (k - 0.5) steps (a little
    // over: the plane's distances are measured from the pixels' centres).
    const GatherRadii& radii = ctx.gather_radii();
    auto centre = [&](int x, int y) {
        const Vec3 d = ctx.camera.direction(x + 0.5f, y + 0.5f);
        return ctx.camera.position() + d * (-ctx.camera.position().y / d.y);  // on the plate, y = 0
    };
    for (int k = 0; k < 2; ++k) {
        SCOPED_TRACE(::testing::Message() << k + 1 << " pixels in");
        const int x = free_side + k * inward;
        const EdgeCut* cut = radii.cut(static_cast<size_t>(20) * kRes + x);
        ASSERT_NE(cut, nullptr);
        EXPECT_FLOAT_EQ(radius(x, 20), r0);
        EXPECT_LE(radius(x, 20) * cut->shrunk, (k + 0.55f) * step);
        const Vec3 across = decode_normal(cut->across), normal = decode_normal(cut->normal);
        EXPECT_NEAR(across.x, x_runs_along ? -1.0f : 1.0f, 1e-3f);  // over the plate's free edge, x = -0.2
        EXPECT_NEAR(normal.y, 1.0f, 1e-3f);
        EXPECT_NEAR(cut->offset - dot(across, centre(x, 20)), (k + 0.5f) * step, 0.05f * step);
        EXPECT_LT(cut->offset, 0.2f + 1e-4f);  // never past the plate's own edge
    }
    // The plate's corner: the line accounts for one edge (the region a cut keeps is checked,
    // ray by ray), the other still caps the radius.
    const int corner_y = 10;
    const EdgeCut* corner = radii.cut(static_cast<size_t>(corner_y) * kRes + free_side + inward);
    EXPECT_LE(radius(free_side + inward, corner_y), 1.55f * step);
    ASSERT_NE(corner, nullptr);
    EXPECT_LE(radius(free_side + inward, corner_y) * corner->shrunk, 0.55f * step);
    EXPECT_FLOAT_EQ(radius(free_side + 4 * inward, 20), r0);
    EXPECT_EQ(radii.cut(static_cast<size_t>(20) * kRes + free_side + 4 * inward), nullptr);
    // The plate's far corner toward the wall: the wall is no edge. Its own top edge is seen
    // edge-on from above: the pixels next to it on the plate keep r0 (the wall's hits rise).
    const int by_wall = x_runs_along ? 24 : 15;  // the plate's last pixel before x = 0.1
    EXPECT_FLOAT_EQ(radius(by_wall, 20), r0);
    EXPECT_EQ(radii.cut(static_cast<size_t>(20) * kRes + by_wall), nullptr);
    // The floor round the plate: the plate stands over it, nearer the eye, so it is no edge for
    // the floor, right beside the plate too.
    EXPECT_FLOAT_EQ(radius(free_side - inward, 20), r0);
    EXPECT_EQ(radii.cut(static_cast<size_t>(20) * kRes + free_side - inward), nullptr);
}

}  // namespace
}  // namespace sl

namespace sl {
namespace {

TEST(AutomaticRadius, APulseStartsWiderByItsFramesToTheSixth) {
    // A pulse's frame holds only the photons that arrive in it: its discs start
    // (frames / pulse frames)^(1/6) wider than constant light's, at most twice as wide.
    SceneDesc s = plate_in_a_beam();
    s.time = {0, 96, 48, 24};
    const float steady = RenderContext(s).initial_radius;
    s.emission.mode = EmissionMode::Pulse;
    EXPECT_NEAR(RenderContext(s).initial_radius / steady, std::pow(48.0, 1.0 / 6), 1e-4);
    s.emission.width_ns = 4, s.emission.width_frames = 2;
    EXPECT_NEAR(RenderContext(s).initial_radius / steady, std::pow(24.0, 1.0 / 6), 1e-4);
    s.time = {0, 8192, 4096, 24};
    s.emission.width_ns = 0, s.emission.width_frames = 1;
    EXPECT_NEAR(RenderContext(s).initial_radius / steady, 2.0, 1e-4);
    s.render.radius = 0.05f;  // the scene's own radius is kept as it is
    EXPECT_FLOAT_EQ(RenderContext(s).initial_radius, 0.05f);
}

}  // namespace
}  // namespace sl
