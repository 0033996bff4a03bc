// A pulse through a glass slab of thickness d arrives (n - 1) d / c later than beside it.
//
// Two identical lasers shine perpendicularly onto a diffuse receiver 1 m away; a dielectric box
// (n = 1.5, d = 0.3 m) stands in the path of one of them. At normal incidence the beam is not
// bent, so its path through the slab is exactly d, crossed at c/n instead of c: the extra time is
// (n - 1) d / c = 0.5003 ns = 10.0 buckets of 0.05 ns. The beam is collimated and the receiver
// perpendicular, so each spot's light arrives in one single bucket, which the test finds.
//
// max_depth: the slab's two interfaces are scattering vertices (specular ones), so the beam through
// the slab reaches the camera after 3 vertices (interface, interface, receiver). With max_depth 2
// that spot must stay dark while the other one is lit; with max_depth 3 both are lit, and the
// slab's spot holds the Fresnel transmittance (1 - R)^2, R = ((n - 1) / (n + 1))^2, of the other.
//
// The camera's way back through glass (camera_tof) is checked too: see the last test.
#include <gtest/gtest.h>

#include <cmath>

#include "light_paths_helpers.h"

namespace sl {
namespace {

using lp::kC;

constexpr float kN = 1.5f, kD = 0.3f, kL = 1.0f;  // ior, slab thickness, laser-to-receiver length
constexpr float kBeamR = 0.1f, kSpotX = 0.3f, kGroupR = 0.065f;

SceneDesc slab_scene(int max_depth) {
    SceneDesc s = lp::empty_scene({0, 1.6f, 1.4f}, {0, 0, 0}, {0, 1, 0}, 30, 64);
    int grey = lp::add_material(s, MaterialType::Diffuse, Vec3(0.8f));
    int glass = lp::add_material(s, MaterialType::Dielectric, Vec3(1), kN);
    lp::add_quad(s, {-2, -2, 0}, {4, 0, 0}, {0, 4, 0}, grey);  // receiver z = 0, facing +z
    // The slab covers the left half of the beams' region: z in [0.4, 0.7], so d = 0.3 m.
    lp::add_box(s, {-1, -0.2f, 0.4f}, {-0.12f, 0.2f, 0.4f + kD}, glass);
    lp::add_laser(s, {-kSpotX, 0, kL}, {0, 0, -1}, kBeamR, 10);  // through the slab
    lp::add_laser(s, {+kSpotX, 0, kL}, {0, 0, -1}, kBeamR, 10);  // beside it
    s.time = {0, 5, 100, 24};  // delta = 0.05 ns
    s.render.max_depth = max_depth;
    s.render.passes = 4;
    s.render.photons_per_pass = 40000;
    s.render.radius = 0.01f;
    return s;
}

struct Spot {
    std::vector<double> profile;  // summed over the spot's pixels, per pulse frame
    double total = 0;             // steady
    int pixels = 0;
    int peak() const { return int(std::max_element(profile.begin(), profile.end()) - profile.begin()); }
    int first(double frac) const {
        double sum = 0;
        for (double v : profile) sum += v;
        for (size_t f = 0; f < profile.size(); ++f)
            if (profile[f] > frac * sum) return int(f);
        return -1;
    }
};

// The pixels whose centre sees the receiver within kGroupR of (cx, 0, 0).
Spot spot(const SceneDesc& s, const lp::Rendered& r, float cx) {
    PinholeCamera cam(s.camera);
    Spot out;
    out.profile.assign(r.frames.size(), 0.0);
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            Vec3 p = lp::on_plane(cam, x + 0.5f, y + 0.5f, {0, 0, 1}, 0);
            if (std::hypot(p.x - cx, p.y) > kGroupR) continue;
            ++out.pixels;
            for (size_t f = 0; f < r.frames.size(); ++f) out.profile[f] += r.pixel(int(f), x, y);
            out.total += r.steady_at(x, y);
        }
    return out;
}

TEST(GlassSlab, PulseThroughSlabArrivesLaterByNMinusOneDOverC) {
    SceneDesc s = slab_scene(3);
    lp::Rendered r = lp::render_all(s);
    Spot glass = spot(s, r, -kSpotX), air = spot(s, r, +kSpotX);
    ASSERT_GT(glass.pixels, 20);
    ASSERT_GT(air.pixels, 20);
    ASSERT_GT(glass.total, 0);
    ASSERT_GT(air.total, 0);
    const double delta = timeline_of(s).delta();
    const double t_air = kL / kC, t_glass = (kL - kD + kN * kD) / kC;
    const int b_air = lp::bucket_of(t_air, delta), b_glass = lp::bucket_of(t_glass, delta);
    const double expected_delay = (kN - 1) * kD / kC;
    // Both fronts arrive in exactly their bucket: the bucket of the path length at c (and c/n).
    EXPECT_EQ(air.peak(), b_air);
    EXPECT_EQ(glass.peak(), b_glass);
    EXPECT_EQ(air.first(1e-3), b_air);
    EXPECT_EQ(glass.first(1e-3), b_glass);
    const int measured = glass.first(1e-3) - air.first(1e-3);
    EXPECT_NEAR(measured * delta, expected_delay, delta);
    // Collimated beam, perpendicular receiver: (nearly) all of a spot's light is in that bucket.
    // (Photons reflected twice inside the slab arrive 2 n d / c later: R^2 = 0.16% of them.)
    EXPECT_GT(air.profile[b_air] / air.total, 0.995);
    EXPECT_GT(glass.profile[b_glass] / glass.total, 0.99);
    // Energy: the slab's spot holds (1 - R)^2 of the other one (at max_depth 3, no inner echoes).
    const double R = std::pow((kN - 1) / (kN + 1), 2);
    const double ratio = (glass.total / glass.pixels) / (air.total / air.pixels);
    EXPECT_NEAR(ratio, (1 - R) * (1 - R), 0.03);
    std::printf("[glass slab] arrival bucket beside %d (t = %.4f ns), through %d (t = %.4f ns): measured delay "
                "%.3f ns (%d buckets), expected (n-1)d/c = %.4f ns; transmitted ratio %.4f, expected (1-R)^2 = %.4f\n",
                air.first(1e-3), t_air, glass.first(1e-3), t_glass, measured * delta, measured, expected_delay, ratio,
                (1 - R) * (1 - R));
}

// Rough glass (GGX, Walter et al.) changes medium and index as smooth glass does: each leg's
// time is its length x the index / c, so the pulse through a nearly smooth rough slab arrives in
// the smooth slab's bucket, 10 buckets after the one beside it, with about the same energy.
TEST(GlassSlab, PulseThroughRoughSlabArrivesAsThroughTheSmoothOne) {
    SceneDesc s = slab_scene(3);
    s.materials[1].type = MaterialType::RoughDielectric;
    s.materials[1].roughness = 0.1f;
    lp::Rendered r = lp::render_all(s);
    Spot glass = spot(s, r, -kSpotX), air = spot(s, r, +kSpotX);
    ASSERT_GT(glass.total, 0);
    ASSERT_GT(air.total, 0);
    const double delta = timeline_of(s).delta();
    const int b_air = lp::bucket_of(kL / kC, delta), b_glass = lp::bucket_of((kL - kD + kN * kD) / kC, delta);
    EXPECT_EQ(air.first(1e-3), b_air);
    EXPECT_EQ(glass.peak(), b_glass);
    EXPECT_EQ(glass.first(1e-3), b_glass);
    EXPECT_GT(glass.profile[b_glass] / glass.total, 0.98);
    const double R = std::pow((kN - 1) / (kN + 1), 2);
    const double ratio = (glass.total / glass.pixels) / (air.total / air.pixels);
    EXPECT_NEAR(ratio, (1 - R) * (1 - R), 0.05);
    std::printf("[rough glass slab, roughness 0.1] arrival bucket through %d (smooth slab's %d), %.4f of the spot's "
                "light in it; transmitted ratio %.4f, smooth (1-R)^2 = %.4f\n",
                glass.first(1e-3), b_glass, glass.profile[b_glass] / glass.total, ratio, (1 - R) * (1 - R));
}

TEST(GlassSlab, SlabInterfacesCountTowardsMaxDepth) {
    SceneDesc s = slab_scene(2);
    s.render.passes = 2;
    lp::Rendered r = lp::render_all(s);
    Spot glass = spot(s, r, -kSpotX), air = spot(s, r, +kSpotX);
    EXPECT_GT(air.total, 0);
    EXPECT_EQ(glass.total, 0) << "light through two interfaces needs max_depth >= 3";
}

// The camera's way back goes through glass too: a camera 3 m in front of a plane looks at it
// through a slab (n = 1.5, d = 0.3 m, 1.0 .. 1.3 m from the plane) that covers the left half of
// its view. With camera_tof, a pixel seen through the slab is later than without by the
// refracted camera leg, (l_air + n l_glass) / c, which exceeds the straight |x - camera| / c by
// about (n - 1) d / c = 10 buckets of 0.05 ns. Each pixel's leg is computed by Snell's law.
// max_depth 3: light -> plane -> interface -> interface -> camera.
TEST(GlassSlab, CameraLegThroughGlassTravelsAtCOverN) {
    constexpr int kRes = 48;
    constexpr float kCamZ = 3, kTop = 1.3f, kBottom = 1.0f;
    const Vec3 cam_pos{0, 0, kCamZ}, light{1.0f, 0, 0.5f};  // below the slab: no shadow through glass
    SceneDesc s = lp::empty_scene(cam_pos, {0, 0, 0}, {0, 1, 0}, 16, kRes);
    int grey = lp::add_material(s, MaterialType::Diffuse, Vec3(0.8f));
    int glass = lp::add_material(s, MaterialType::Dielectric, Vec3(1), kN);
    lp::add_quad(s, {-3, -3, 0}, {6, 0, 0}, {0, 6, 0}, grey);
    lp::add_box(s, {-2, -2, kBottom}, {0, 2, kTop}, glass);
    lp::add_point_light(s, light, 50);
    s.time = {0, 16, 320, 24};  // delta = 0.05 ns
    s.render.max_depth = 3;
    // 8% of camera paths reflect off the slab (Fresnel) and find no visible point: with 8
    // passes every pixel still gets light in some pass.
    s.render.passes = 8;
    s.render.photons_per_pass = 100;
    s.render.radius = 0.005f;
    const double delta = timeline_of(s).delta();
    s.render.camera_tof = false;
    lp::Rendered no = lp::render_all(s);
    s.render.camera_tof = true;
    lp::Rendered yes = lp::render_all(s);
    PinholeCamera cam(s.camera);
    // The camera ray through (fx, fy): where it meets the plane, and its length in ns (glass at c/n).
    auto trace = [&](float fx, float fy, bool& through, double& leg_ns) {
        Vec3 d = cam.direction(fx, fy);
        float t_top = (kTop - kCamZ) / d.z;
        Vec3 q = cam_pos + d * t_top;
        through = q.x < 0;
        if (!through) {
            Vec3 p = cam_pos + d * (-kCamZ / d.z);
            leg_ns = length(p - cam_pos) / kC;
            return p;
        }
        double cos_i = -d.z, sin_i = std::sqrt(std::max(0.0, 1 - cos_i * cos_i));
        double sin_t = sin_i / kN, cos_t = std::sqrt(1 - sin_t * sin_t);
        double in_glass = (kTop - kBottom) / cos_t;
        Vec3 lateral = normalize(Vec3{d.x, d.y, 0});
        if (!(sin_i > 0)) lateral = Vec3{0, 0, 0};
        Vec3 exit = q + lateral * float(in_glass * sin_t) + Vec3{0, 0, -(kTop - kBottom)};
        Vec3 p = exit + d * (-exit.z / d.z);  // leaves parallel to the way it came in
        leg_ns = (t_top + length(p - exit) + kN * in_glass) / kC;
        return p;
    };
    int checked_glass = 0, checked_air = 0, bad = 0;
    double worst = 0, glass_excess = 0;
    for (int y = 0; y < kRes; ++y)
        for (int x = 0; x < kRes; ++x) {
            bool th_c, th;
            double leg_c, leg, lo = 1e300, hi = -1e300;
            Vec3 pc = trace(x + 0.5f, y + 0.5f, th_c, leg_c);
            bool mixed = false;
            for (int i = 0; i <= 2; ++i)
                for (int j = 0; j <= 2; ++j) {
                    trace(x + 0.5f * i, y + 0.5f * j, th, leg);
                    mixed |= th != th_c;
                    lo = std::min(lo, leg);
                    hi = std::max(hi, leg);
                }
            if (mixed || hi - lo >= 0.5 * delta) continue;
            lp::Arrival a0 = lp::arrival(no, x, y), a1 = lp::arrival(yes, x, y);
            ASSERT_GE(a0.first, 0) << "pixel " << x << "," << y;
            ASSERT_GE(a1.first, 0) << "pixel " << x << "," << y;
            // Without tof: the light-to-point time of the (refracted) visible point.
            EXPECT_NEAR(a0.first, lp::bucket_of(length(pc - light) / kC, delta), 1) << x << "," << y;
            const int expected = static_cast<int>(std::lround(leg_c / delta));
            const int shift = a1.first - a0.first;
            worst = std::max(worst, double(std::abs(shift - expected)));
            if (std::abs(shift - expected) > 1 && ++bad <= 5)
                ADD_FAILURE() << "pixel " << x << "," << y << (th_c ? " (through glass)" : " (beside)") << ": shift "
                              << shift << ", expected " << expected << " (at c all the way: "
                              << std::lround(length(pc - cam_pos) / kC / delta) << ")";
            if (th_c) {
                ++checked_glass;
                glass_excess += (leg_c - length(pc - cam_pos) / kC) / delta;
            } else {
                ++checked_air;
            }
        }
    EXPECT_GT(checked_glass, 500);
    EXPECT_GT(checked_air, 500);
    EXPECT_EQ(bad, 0);
    glass_excess /= checked_glass;
    EXPECT_NEAR(glass_excess * delta, (kN - 1) * kD / kC, 0.1 * delta) << "geometry check";
    std::printf("[glass slab, camera leg] %d pixels through glass, %d beside: worst |tof shift - refracted leg| = "
                "%.0f bucket; the glass adds %.2f buckets (%.4f ns) on average, (n-1)d/c = %.4f ns\n",
                checked_glass, checked_air, worst, glass_excess, glass_excess * delta, (kN - 1) * kD / kC);
}

}  // namespace
}  // namespace sl
