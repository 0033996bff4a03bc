// The sun light against geometry: its photons carry E x (area facing the sun) through a window,
// and, rendered, sunlight through a hole in a closed box's ceiling lights exactly the floor
// patch the window casts along the sun's direction, with radiance E cos(theta) albedo / pi,
// first in the frame in which the plane wavefront (entering the box's bounds at t = 0) reaches
// each point.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "foundation/errors.h"
#include "core/light_set.h"
#include "core/sun_light.h"
#include "render_helpers.h"
#include "scenes_for_tests.h"

namespace sl {
namespace {

constexpr double kC = 0.299792458;  // m/ns

// The sun's wavefront at t = 0 is the plane through the bounds' first corner along d.
double entry_plane(Vec3 d, Vec3 lo, Vec3 hi) {
    double h = 1e300;
    for (int c = 0; c < 8; ++c)
        h = std::min<double>(h, dot(Vec3{(c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z}, d));
    return h;
}

// Photons from the sun that cross a horizontal window carry E |d.y| x the window's area, and
// reach it at the time the plane wavefront gives.
TEST(SunLight, PhotonFluxThroughAWindowIsIrradianceTimesProjectedArea) {
    SceneDesc s;
    const Vec3 d = normalize(Vec3{0.6f, -1, -0.3f});
    s.lights.push_back(make_sun_light(d, 0.53f, {900, 600, 300}));
    const Vec3 lo{-3, 0, -2}, hi{5, 4, 3};
    LightSet lights(s, lo, hi);
    const double h0 = entry_plane(d, lo, hi);
    // The window: y = 2, x in [0, 1.5], z in [-0.5, 0.5] (1.5 m^2).
    const int n = 400000;
    Rng rng(7, 0, 0, 0);
    double flux[3] = {0, 0, 0};
    double worst_dt = 0;
    int through = 0;
    for (int i = 0; i < n; ++i) {
        EmittedPhoton e = lights.emit(rng);
        const float t = (2 - e.origin.y) / e.direction.y;
        const Vec3 x = e.origin + e.direction * t;
        if (!(t > 0) || x.x < 0 || x.x > 1.5f || x.z < -0.5f || x.z > 0.5f) continue;
        ++through;
        for (int c = 0; c < 3; ++c) flux[c] += e.flux[c] / n;
        const double arrival = e.start_ns + t / kC, want = (dot(x, d) - h0) / kC;
        worst_dt = std::max(worst_dt, std::abs(arrival - want));
    }
    const double want[3] = {900 * 1.5 * -d.y, 600 * 1.5 * -d.y, 300 * 1.5 * -d.y};
    std::printf("through the window: %d photons, flux %.2f %.2f %.2f W (want %.2f %.2f %.2f), worst time %.2g ns\n",
                through, flux[0], flux[1], flux[2], want[0], want[1], want[2], worst_dt);
    ASSERT_GT(through, 1000);
    const double rel = 3 / std::sqrt(static_cast<double>(through));  // three standard errors
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(flux[c], want[c], rel * want[c]) << "channel " << c;
    EXPECT_LT(worst_dt, 2e-3);  // a tilt of 0.27 degrees adds ~1e-5 of the path at most
}

TEST(SunLight, LightsTheFloorPatchThroughAWindowWhenThePlaneWavefrontArrives) {
    const Vec3 d = normalize(Vec3{0.3f, -1, 0.2f});
    const Vec3 E{800, 700, 500};
    const float rho = 0.6f;
    SceneDesc s = test::box_with_a_window(d, E, rho);
    test::Rendered r = test::render_all(s);
    const double h0 = entry_plane(d, {0, 0, 0}, {4, 3, 4});

    // The patch: the window moved along d down to the floor, x in [1.5, 2.5] + dx, z likewise.
    const float dx = d.x * (3 / -d.y), dz = d.z * (3 / -d.y);
    const float x0 = 1.5f + dx, x1 = 2.5f + dx, z0 = 1.5f + dz, z1 = 2.5f + dz;
    const float pen = 3 * std::tan(0.53f * 3.14159265f / 180) / -d.y + 1e-3f;  // penumbra, with margin
    const float cos_t = -d.y;
    const Vec3 want = E * (cos_t * rho / 3.14159265f);

    PinholeCamera cam(s.camera);
    auto floor_at = [&](float px, float py) {  // where the ray through an image point meets y = 0
        Vec3 w = cam.direction(px, py);
        return cam.position() + w * (-cam.position().y / w.y);
    };
    const Timeline tl{s.time.start_ns, s.time.end_ns, s.time.frames};
    int inside = 0, outside = 0, timed = 0;
    double sum_in[3] = {0, 0, 0}, worst_in = 0, leak = 0, lit_power = 0;
    for (int y = 0; y < s.camera.height; ++y)
        for (int x = 0; x < s.camera.width; ++x) {
            const size_t p = static_cast<size_t>(y) * s.camera.width + x;
            float lx = 1e30f, hx = -1e30f, lz = 1e30f, hz = -1e30f;
            double tmin = 1e300, tmax = -1e300;
            for (int c = 0; c < 4; ++c) {
                Vec3 f = floor_at(static_cast<float>(x + (c & 1)), static_cast<float>(y + (c >> 1)));
                lx = std::min(lx, f.x); hx = std::max(hx, f.x);
                lz = std::min(lz, f.z); hz = std::max(hz, f.z);
                const double t = (dot(f, d) - h0) / kC;
                tmin = std::min(tmin, t); tmax = std::max(tmax, t);
            }
            if (lx < 0 || hx > 4 || lz < 0 || hz > 4) continue;  // not all floor
            const float* L = &r.steady[p * 3];
            const float area = (hx - lx) * (hz - lz);
            lit_power += (L[0] + L[1] + L[2]) / 3 * area;
            const bool all_in = lx > x0 + pen && hx < x1 - pen && lz > z0 + pen && hz < z1 - pen;
            const bool all_out = hx < x0 - pen || lx > x1 + pen || hz < z0 - pen || lz > z1 + pen;
            if (all_out) {
                ++outside;
                leak += L[0] + L[1] + L[2];
                continue;
            }
            if (!all_in) continue;
            ++inside;
            for (int c = 0; c < 3; ++c) {
                sum_in[c] += L[c];
                worst_in = std::max(worst_in, std::abs(double(L[c]) / want[c] - 1));
            }
            // The first frame with light must be the bucket of an arrival time in the pixel.
            int first = -1;
            for (int k = 0; k < s.time.frames && first < 0; ++k)
                if (r.frames[k][p * 3] > 0) first = k;
            const int64_t lo = tl.bucket(tmin), hi = tl.bucket(tmax + 1e-3);
            EXPECT_GE(first, lo) << "pixel " << x << "," << y << " lit before the wavefront reaches it";
            EXPECT_LE(first, hi) << "pixel " << x << "," << y << " lit late";
            timed += first >= lo && first <= hi;
        }
    for (double& v : sum_in) v /= inside;
    // Total: the window's 1 m^2 of light lands on the floor (the patch is 1 m^2 too).
    const double want_power = (want[0] + want[1] + want[2]) / 3 * 1.0;
    std::printf("sun patch: %d pixels inside (%d on time), %d outside; radiance %.3f %.3f %.3f (want %.3f %.3f %.3f), "
                "worst pixel %.2g, leak %.3g, light on the floor %.4f of E cos rho/pi x 1 m^2\n",
                inside, timed, outside, sum_in[0], sum_in[1], sum_in[2], want[0], want[1], want[2], worst_in, leak,
                lit_power / want_power);
    ASSERT_GT(inside, 100);
    ASSERT_GT(outside, 1000);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum_in[c], want[c], 2e-3 * want[c]);
    EXPECT_LT(worst_in, 0.01);
    EXPECT_EQ(leak, 0.0);  // nothing outside the patch: no light through the ceiling or walls
    EXPECT_NEAR(lit_power / want_power, 1.0, 0.03);  // its size: edge pixels are partly lit
    // The patch's far edge is lit later than its near one: the wavefront is a plane moving along d.
    EXPECT_GT(tl.bucket((dot(Vec3{x1, 0, z1}, d) - h0) / kC), tl.bucket((dot(Vec3{x0, 0, z0}, d) - h0) / kC) + 1);
}

}  // namespace
}  // namespace sl

namespace sl {
namespace {

// A sun's power is its irradiance times the scene's cross-section: a huge scene and a huge
// irradiance overflow single precision, which must be an input error, not NaN frames.
TEST(SunLight, PowerTooLargeForSinglePrecisionIsAnInputError) {
    SceneDesc s;
    s.source = "huge.json";
    s.lights.push_back(make_sun_light({0.3f, -1, 0}, 0.53f, Vec3(1e30f)));
    EXPECT_NO_THROW(LightSet(s, Vec3(-1), Vec3(1)));
    try {
        LightSet(s, Vec3(-1e8f), Vec3(1e8f));
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("huge.json: key 'lights[0]'"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace sl
