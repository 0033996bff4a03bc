// Mirror: the image of a light in a mirror lights up when the reflected path length says so.
//
// 1. A spot light aims at a plane mirror; a diffuse receiver behind the spot gets light only by
//    way of the mirror (it lies outside the spot's cone). For a plane mirror the reflected path
//    light -> mirror -> x has the length |x - light'|, light' being the light's mirror image, so
//    the receiver must light up at |x - light'| / c (not at the direct |x - light| / c, a third
//    of it here), and with camera_tof at (|x - light'| + |x - camera|) / c. The light
//    arrives by photons (the mirror vertex makes it indirect), so a pixel's arrival is its
//    energy-weighted mean frame, which must match the bucket of the pixel-centre path +- 1 (the
//    gather radius and the pixel footprint are a third of a bucket). Its radiance must also be
//    that of the image light: rho/pi * reflectance * I cos / |x - light'|^2, I = P / (2 pi (1 - cos))
//    (a separate test, below).
// 2. The camera sees a floor through a mirror with camera_tof: the way back to the camera goes
//    through the mirror, so the arrival is later by |x - camera'| / c (camera' the camera's mirror
//    image), not by the straight |x - camera| / c.
#include <gtest/gtest.h>

#include <cmath>

#include "light_paths_helpers.h"

namespace sl {
namespace {

using lp::kC;

constexpr float kRho = 0.5f, kRefl = 0.9f, kSpotP = 20, kCone = 10;

// Spot at the origin pointing +x at the mirror x = 1; receiver x = -1 facing +x; camera at
// x = 0.5 looking at the receiver (neither the camera nor the spot is geometry).
SceneDesc spot_mirror_scene(int max_depth, bool tof) {
    SceneDesc s = lp::empty_scene({0.5f, 0, 0}, {-1, 0, 0}, {0, 1, 0}, 50, 48);
    int grey = lp::add_material(s, MaterialType::Diffuse, Vec3(kRho));
    int mirror = lp::add_material(s, MaterialType::Mirror, Vec3(kRefl));
    lp::add_quad(s, {-1, -3, 3}, {0, 0, -6}, {0, 6, 0}, grey);  // receiver x = -1
    lp::add_quad(s, {1, -3, -3}, {0, 0, 6}, {0, 6, 0}, mirror);  // mirror x = 1
    lp::add_spot(s, {0, 0, 0}, {1, 0, 0}, kCone, kSpotP);
    s.time = {0, 16, 160, 24};  // delta = 0.1 ns
    s.render.max_depth = max_depth;
    s.render.camera_tof = tof;
    s.render.passes = 8;
    s.render.photons_per_pass = 100000;
    s.render.radius = 0.01f;
    return s;
}

struct ImageCheck {
    int checked = 0, bad = 0, dark_ok = 0;
    double worst_mean_err = 0;  // buckets
    double radiance_ratio = 0;  // rendered / image light's, summed over the checked pixels
};

ImageCheck check_spot_image(bool tof) {
    const Vec3 image{2, 0, 0};  // the spot's image in the mirror x = 1
    const Vec3 spot_pos{0, 0, 0};
    const double cos_cone = std::cos(kCone * kPi / 180);
    const double I = kSpotP / (2 * M_PI * (1 - cos_cone));
    SceneDesc s = spot_mirror_scene(2, tof);
    lp::Rendered r = lp::render_all(s);
    PinholeCamera cam(s.camera);
    const double delta = timeline_of(s).delta();
    ImageCheck out;
    double sum_got = 0, sum_want = 0;
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            Vec3 p = lp::on_plane(cam, x + 0.5f, y + 0.5f, {1, 0, 0}, -1);
            Vec3 to_p = normalize(p - image);
            double cos_axis = dot(to_p, Vec3{-1, 0, 0});  // angle from the reflected axis
            double ang = std::acos(std::min(1.0, cos_axis)) * 180 / M_PI;
            lp::Arrival a = lp::arrival(r, x, y);
            if (ang > kCone + 2.5) {  // well outside the reflected cone (pixel + gather radius)
                EXPECT_EQ(a.total, 0) << "pixel " << x << "," << y;
                ++out.dark_ok;
                continue;
            }
            if (ang > kCone - 2.5) continue;  // the cone's edge, blurred by gathering
            double t = length(p - image) / kC + (tof ? length(p - cam.position()) / kC : 0);
            // A pixel's light arrives within a fraction of a bucket (its path lengths vary by
            // < 1 cm over the pixel and gather disk): its mean frame is the bucket of t, or lies
            // between it and a neighbour when the pixel straddles a bucket edge.
            double want_mean = lp::bucket_of(t, delta);
            ++out.checked;
            if (!(a.total > 0)) {
                ++out.bad;
                ADD_FAILURE() << "pixel " << x << "," << y << " dark inside the reflected cone";
                continue;
            }
            out.worst_mean_err = std::max(out.worst_mean_err, std::abs(a.mean - want_mean));
            if (std::abs(a.mean - want_mean) > 1.0 && ++out.bad <= 5)
                ADD_FAILURE() << "pixel " << x << "," << y << ": mean arrival frame " << a.mean << ", expected "
                              << want_mean << " (t = " << t << " ns)";
            // The direct path (spot -> x) is far shorter: nothing may arrive that early.
            double t_direct = length(p - spot_pos) / kC + (tof ? length(p - cam.position()) / kC : 0);
            EXPECT_GT(a.first, lp::bucket_of(t_direct, delta) + 10);
            double r2 = dot(p - image, p - image);
            double cos_x = std::abs(to_p.x);
            sum_want += kRho / M_PI * kRefl * I * cos_x / r2;
            sum_got += r.steady_at(x, y);
        }
    out.radiance_ratio = sum_got / sum_want;
    return out;
}

TEST(Mirror, ImageOfSpotInMirrorLightsUpAtReflectedPathLength) {
    for (bool tof : {false, true}) {
        ImageCheck c = check_spot_image(tof);
        EXPECT_GT(c.checked, 200);
        EXPECT_GT(c.dark_ok, 200);
        EXPECT_EQ(c.bad, 0);
        std::printf("[mirror, spot image%s] %d pixels: worst |mean arrival frame - bucket of reflected path| = %.2f "
                    "buckets\n",
                    tof ? ", camera_tof" : "", c.checked, c.worst_mean_err);
    }
}

// Regression test: exposed the photon-gather bug (PhotonMap::for_each_near visits at most 8 of the up
// to 27 grid cells a gather sphere overlaps): the rendered radiance is 0.578 of the image
// light's. With the fix: 1.001.
TEST(Mirror, ImageOfSpotHasTheImageLightsRadiance) {
    ImageCheck c = check_spot_image(false);
    EXPECT_GT(c.checked, 200);
    EXPECT_NEAR(c.radiance_ratio, 1.0, 0.05);
    std::printf("[mirror, spot image] radiance / image-light radiance = %.4f\n", c.radiance_ratio);
}

TEST(Mirror, MirrorVertexCountsTowardsMaxDepth) {
    SceneDesc s = spot_mirror_scene(1, false);
    s.render.passes = 1;
    lp::Rendered r = lp::render_all(s);
    double sum = 0;
    for (float v : r.steady) sum += v;
    EXPECT_EQ(sum, 0) << "light -> mirror -> receiver -> camera has 2 vertices: max_depth 1 shows nothing";
}

// Floor y = 0 under a downward spot; mirror x = 1; the camera at x = -1 sees the floor only in the mirror.
TEST(Mirror, CameraTofGoesBackThroughTheMirror) {
    constexpr int kRes = 48;
    // Looking down at 45 degrees into the mirror, which shows the floor around the origin; a
    // narrow field keeps a pixel's camera distance within a quarter of a bucket.
    const Vec3 cam_pos{-1, 3, 0}, light{0, 1, 0};
    SceneDesc s = lp::empty_scene(cam_pos, {1, 1, 0}, {0, 1, 0}, 10, kRes);
    int grey = lp::add_material(s, MaterialType::Diffuse, Vec3(kRho));
    int mirror = lp::add_material(s, MaterialType::Mirror, Vec3(kRefl));
    lp::add_quad(s, {-5, 0, 5}, {10, 0, 0}, {0, 0, -10}, grey);  // floor, facing +y
    lp::add_quad(s, {1, 0, -3}, {0, 0, 6}, {0, 3, 0}, mirror);     // mirror x = 1 (y in [0, 3])
    // Spot straight down, 30 degree cone: it lights the floor disk r < 0.577 and never the mirror.
    lp::add_spot(s, light, {0, -1, 0}, 30, 20);
    s.time = {0, 24, 120, 24};  // delta = 0.2 ns
    s.render.max_depth = 2;     // light -> floor -> mirror -> camera
    s.render.passes = 4;
    s.render.photons_per_pass = 1000;
    const double delta = timeline_of(s).delta();
    s.render.camera_tof = false;
    lp::Rendered no = lp::render_all(s);
    s.render.camera_tof = true;
    lp::Rendered yes = lp::render_all(s);

    PinholeCamera cam(s.camera);
    const Vec3 cam_image{3, 3, 0};  // the camera's image in the mirror x = 1
    // Follows the camera ray through (fx, fy): reflected by the mirror if it meets it first.
    auto trace = [&](float fx, float fy, bool& via_mirror) {
        Vec3 d = cam.direction(fx, fy), o = cam.position();
        float t_floor = d.y < 0 ? -o.y / d.y : 1e30f;
        float t_mirror = d.x > 0 ? (1 - o.x) / d.x : 1e30f;
        via_mirror = t_mirror < t_floor && o.y + d.y * t_mirror >= 0;
        if (!via_mirror) return o + d * t_floor;
        Vec3 m = o + d * t_mirror, d2{-d.x, d.y, d.z};
        return m + d2 * (-m.y / d2.y);
    };
    int checked_mirror = 0, checked_direct = 0, bad = 0;
    double worst = 0;
    for (int y = 0; y < kRes; ++y)
        for (int x = 0; x < kRes; ++x) {
            // Only pixels wholly through the mirror (or wholly direct) and wholly inside the lit disk.
            int via = 0;
            double b_lo = 1e300, b_hi = -1e300;
            bool lit = true;
            Vec3 pc;
            for (int i = 0; i <= 2; ++i)
                for (int j = 0; j <= 2; ++j) {
                    bool vm;
                    Vec3 p = trace(x + 0.5f * i, y + 0.5f * j, vm);
                    via += vm;
                    if (i == 1 && j == 1) pc = p;
                    if (std::hypot(p.x, p.z) > 0.55) lit = false;
                    double b = (vm ? length(p - cam_image) : length(p - cam_pos)) / kC;
                    b_lo = std::min(b_lo, b);
                    b_hi = std::max(b_hi, b);
                }
            if (!lit || (via != 0 && via != 9) || b_hi - b_lo >= 0.5 * delta) continue;
            lp::Arrival a0 = lp::arrival(no, x, y), a1 = lp::arrival(yes, x, y);
            ASSERT_GE(a0.first, 0) << "pixel " << x << "," << y;
            ASSERT_GE(a1.first, 0) << "pixel " << x << "," << y;
            // Without tof the camera sees the light the instant it reaches the floor.
            EXPECT_NEAR(a0.first, lp::bucket_of(length(pc - light) / kC, delta), 1) << x << "," << y;
            const double back = (via ? length(pc - cam_image) : length(pc - cam_pos)) / kC;
            const int expected = static_cast<int>(std::lround(back / delta));
            const int shift = a1.first - a0.first;
            worst = std::max(worst, double(std::abs(shift - expected)));
            if (std::abs(shift - expected) > 1 && ++bad <= 5)
                ADD_FAILURE() << "pixel " << x << "," << y << (via ? " (via mirror)" : " (direct)") << ": shift "
                              << shift << ", expected " << expected << " (the straight way back would be "
                              << std::lround(length(pc - cam_pos) / kC / delta) << ")";
            (via ? checked_mirror : checked_direct)++;
        }
    EXPECT_GT(checked_mirror, 100);
    EXPECT_EQ(bad, 0);
    std::printf("[mirror, camera leg] %d pixels via the mirror, %d direct: worst |tof shift - (camera' to x)/c| = "
                "%.0f bucket\n",
                checked_mirror, checked_direct, worst);
}

}  // namespace
}  // namespace sl
