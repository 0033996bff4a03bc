// No energy lost to a bounce cap. In a closed room whose walls all have albedo a, every watt
// emitted is absorbed in the end, so the flux arriving at the walls, summed over all bounces,
// is P (1 + a + a^2 + ...) = P / (1 - a) (the integrating sphere's result), and the walls'
// radiance integrates to a P / (pi (1 - a)). A cap of n bounces keeps only 1 - a^n of that:
// at a = 0.9 the old default of 8 lost 43%. The scene leaves render.max_depth at its default.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "render_helpers.h"
#include "scenes_for_tests.h"
#include "stages/render/photon_map.h"

namespace sl {
namespace {

constexpr float kAlbedo = 0.9f, kPower = 1.0f, kHalf = 1.0f;
constexpr double kPiD = 3.14159265358979;

// A 2 m cube, white walls, the light at the centre; the camera at a wall's centre looks at the
// opposite wall, which fills its view exactly.
SceneDesc closed_room(LightType type) {
    SceneDesc s;
    s.source = "<test closed white room>";
    s.camera.position = {0, 0, kHalf * 0.999f};
    s.camera.look_at = {0, 0, -kHalf};
    s.camera.vfov_deg = 2 * std::atan(kHalf / (2 * kHalf * 0.9995f)) * 180 / 3.14159265f;
    s.camera.width = s.camera.height = 16;
    MaterialDesc white;
    white.name = "white";
    white.albedo = Vec3(kAlbedo);
    s.materials.push_back(white);
    for (int axis = 0; axis < 3; ++axis)
        for (float side : {-kHalf, kHalf}) {
            Vec3 c(-kHalf), e1(0), e2(0);
            c[axis] = side;
            e1[(axis + 1) % 3] = 2 * kHalf;
            e2[(axis + 2) % 3] = 2 * kHalf;
            s.shapes.push_back(test::quad(c, e1, e2));
        }
    LightDesc l;
    l.type = type;
    l.position = {0.1f, -0.2f, 0.15f};
    l.direction = {0, -1, 0};
    l.radius = 0.05f;
    l.power = Vec3(kPower);
    s.lights.push_back(l);
    s.time = {0, 400, 1, 24};
    s.render.passes = 8;
    s.render.photons_per_pass = 40000;
    s.render.radius = 0.1f;
    return s;
}

TEST(BounceEnergy, TheDefaultDepthLosesNoLightInAClosedWhiteRoom) {
    // The photon tracer's bookkeeping: a laser stores every wall arrival, its first one too.
    SceneDesc s = closed_room(LightType::Laser);
    s.render.photons_per_pass = 100000;
    RenderContext ctx(s);
    SectionLayout layout = make_section(ctx.timeline, ctx.scene.emission.mode, 1, 0);
    PhotonMap map;
    PhotonTraceCounters counters;
    double sum = 0;
    const int passes = 4;
    for (int pass = 0; pass < passes; ++pass) {
        map.build(ctx, layout, pass, s.render.photons_per_pass, 0.1, counters, nullptr);
        for (const PhotonRecord& r : map.records()) sum += (r.r + r.g + r.b) / 3.0;
    }
    const double got = sum / (static_cast<double>(s.render.photons_per_pass) * passes);
    const double want = kPower / (1 - kAlbedo);
    std::printf("max_depth %d: wall arrivals per path %.4f W, theory %.4f (%+.2f%%)\n", s.render.max_depth, got, want,
                100 * (got / want - 1));
    EXPECT_NEAR(got, want, 0.01 * want);
}

TEST(BounceEnergy, TheRenderedWallHasTheIntegratingSpheresRadiance) {
    // A point light: direct light by shadow rays, the rest by photons. The far wall gets a
    // sixth of the walls' radiance integral by symmetry, less the light's 0.1-0.2 m offset
    // from the centre; measured against the same room's analytic direct part plus a sixth
    // of the indirect part, which is uniform to within the offset's effect on the first bounce.
    SceneDesc s = closed_room(LightType::Point);
    test::Rendered r = test::render_all(s);
    const double pixel_area = (2 * kHalf / r.width) * (2 * kHalf / r.height);
    double integral = 0;
    for (size_t i = 0; i < r.steady.size(); i += 3) integral += (r.steady[i] + r.steady[i + 1] + r.steady[i + 2]) / 3;
    integral *= pixel_area;
    // Direct: the far wall z = -1 sees the light at depth 1.15 over the wall: the solid angle of
    // the wall from the light, times I = P / (4 pi), times a / pi for radiance, integrated over area.
    auto solid_angle = [](double x0, double x1, double y0, double y1, double d) {  // rectangle at distance d
        auto f = [d](double x, double y) { return std::atan(x * y / (d * std::sqrt(x * x + y * y + d * d))); };
        return f(x1, y1) - f(x0, y1) - f(x1, y0) + f(x0, y0);
    };
    const double omega = solid_angle(-kHalf - 0.1, kHalf - 0.1, -kHalf + 0.2, kHalf + 0.2, kHalf + 0.15);
    const double direct = kAlbedo / kPiD * kPower / (4 * kPiD) * omega;
    // Indirect: all bounces after the first, a P a / (1 - a) of flux spread over the six walls.
    const double indirect = kAlbedo / kPiD * kPower * kAlbedo / (1 - kAlbedo) / 6;
    const double want = direct + indirect;
    std::printf("max_depth %d: far wall radiance integral %.4f, theory %.4f (direct %.4f) (%+.2f%%)\n",
                s.render.max_depth, integral, want, direct, 100 * (integral / want - 1));
    EXPECT_NEAR(integral, want, 0.03 * want);
}

}  // namespace
}  // namespace sl
