// No light through a zero-thickness wall. A sheet stands on a floor; a laser beam (every arrival
// is a stored photon, so the floor's light comes through the gather alone) comes down at 45
// degrees from one side and meets the floor at the sheet's foot. The beam never reaches the
// far side (the sheet stops every ray aimed there): the floor beside the foot on the far side
// has no light at all, and on the near side it has rho E / pi with E = P cos 45 / (pi a^2),
// from the beam's flux and cross-section. The old gather took the near side's floor photons
// (same normal, within the radius) into the far side's points, and divided the near side's
// by a whole disc half of which lies beyond the sheet.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "render_helpers.h"
#include "scenes_for_tests.h"

namespace sl {
namespace {

constexpr int kRes = 40;          // the camera sees +-0.4 m of floor: 2 cm a pixel
constexpr float kBeam = 0.3f, kPower = 1, kRho = 0.5f, kRadius = 0.08f;

SceneDesc sheet_on_floor() {
    SceneDesc s = test::looking_down_at_grey("<test sheet wall>", kRes, 0.4f, kRho);
    s.shapes.push_back(test::quad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}));  // the floor
    s.shapes.push_back(test::quad({0, 0, -1}, {0, 0, 2}, {0, 1, 0}));   // the sheet x = 0, 1 m tall
    // Its axis meets the foot at the origin.
    s.lights.push_back(test::laser({1, 1, 0}, Vec3(-1, -1, 0) * (1 / std::sqrt(2.0f)), kBeam, kPower));
    s.time = {0, 100, 2, 24};
    s.render.passes = 8;
    s.render.photons_per_pass = 60000;
    s.render.max_depth = 1;
    s.render.radius = kRadius;
    return s;
}

// Mean of the first channel over columns [c0, c1) and the middle 10 rows (+-0.1 m).
double band(const test::Rendered& r, int c0, int c1) {
    double sum = 0;
    int n = 0;
    for (int y = kRes / 2 - 5; y < kRes / 2 + 5; ++y)
        for (int x = c0; x < c1; ++x, ++n) sum += r.steady[(static_cast<size_t>(y) * kRes + x) * 3];
    return sum / n;
}

TEST(ThinWall, NoLightReachesTheFloorBehindASheetThroughTheGather) {
    const double lit_want = kRho / 3.14159265358979 * kPower * std::sqrt(0.5) / (3.14159265358979 * kBeam * kBeam);
    test::Rendered r = test::render_all(sheet_on_floor());
    // The three columns (6 cm, under one radius) on each side of the sheet, which stands
    // between columns 19 and 20. The lit side is the brighter one (image x may run either way).
    double a = band(r, kRes / 2 - 3, kRes / 2), b = band(r, kRes / 2, kRes / 2 + 3);
    const double dark = std::min(a, b), lit = std::max(a, b);
    // Farther out on the lit side (past the radius from the sheet), as a check of the setup.
    const double lit_far = a > b ? band(r, kRes / 2 - 10, kRes / 2 - 6) : band(r, kRes / 2 + 6, kRes / 2 + 10);
    std::printf("analytic lit %.4f; lit band %.4f (%.3fx), beyond the radius %.4f (%.3fx); dark band %.5f (%.4f of lit)\n",
                lit_want, lit, lit / lit_want, lit_far, lit_far / lit_want, dark, dark / lit_want);
    EXPECT_NEAR(lit_far, lit_want, 0.05 * lit_want);
    EXPECT_LT(dark, 0.005 * lit_want);                // nothing through the sheet
    EXPECT_NEAR(lit, lit_want, 0.05 * lit_want);      // and no dark edge along its foot
}

}  // namespace
}  // namespace sl
