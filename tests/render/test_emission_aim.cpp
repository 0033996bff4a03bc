// Aiming the lights' photons where the camera sees (core/emission_aim.h,
// stages/render/emission_aim_pilot.h): the table draws each cell with its probability and weighs
// the photon back by it; in a closed room lit through a window in its ceiling, by the sun or by
// a lamp above the window, the aimed photons cross the window far more often and carry exactly
// the light's flux through it, as unaimed photons do; a lamp inside the room is left as it
// was; and the rendered room is the same, with less noise.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>

#include "core/light_set.h"
#include "core/rng.h"
#include "core/emission_aim.h"
#include "render_helpers.h"
#include "scenes_for_tests.h"
#include "stages/render/emission_aim_pilot.h"

namespace sl {
namespace {

TEST(EmissionAim, DrawsEachCellByItsProbabilityAndWeighsItBack) {
    const int n = 8;
    std::vector<double> useful(static_cast<size_t>(n) * n, 0.0);
    useful[3] = 1;
    useful[2 * n + 5] = 10;
    useful[7 * n + 7] = 0.5;
    const EmissionAim aim(n, useful, 0.2);
    ASSERT_FALSE(aim.empty());
    Rng rng(11, 0);
    const int draws = 400000;
    std::vector<int> count(useful.size(), 0);
    double factor = 0, factor2 = 0;
    for (int k = 0; k < draws; ++k) {
        float x, y;
        const float w = aim.draw(rng.uniform(), rng.uniform(), x, y);
        ASSERT_TRUE(x >= 0 && x < 1 && y >= 0 && y < 1);
        const int i = static_cast<int>(x * n), j = static_cast<int>(y * n);
        ++count[static_cast<size_t>(j) * n + i];
        // The factor is the uniform draw's density over the cell's.
        EXPECT_NEAR(w, 1.0 / (aim.probability(i, j) * n * n), 1e-4 * w);
        factor += w;
        factor2 += double(w) * w;
    }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double want = aim.probability(i, j) * draws, got = count[static_cast<size_t>(j) * n + i];
            EXPECT_NEAR(got, want, 4 * std::sqrt(want) + 1) << "cell " << i << "," << j;
        }
    // Unbiased: the factor's mean is 1 (the photons carry the sun's power in all).
    const double mean = factor / draws, sd = std::sqrt((factor2 / draws - mean * mean) / draws);
    EXPECT_NEAR(mean, 1.0, 4 * sd);
    // The useful cells take (1 - floor) of the draws in proportion, the floor the rest evenly.
    EXPECT_NEAR(aim.probability(5, 2), 0.8 * 10 / 11.5 + 0.2 / 64, 1e-9);
    EXPECT_NEAR(aim.probability(0, 0), 0.2 / 64, 1e-9);

    // Nothing useful: no table, the rectangle drawn as it is.
    const EmissionAim none(n, std::vector<double>(useful.size(), 0.0), 0.2);
    EXPECT_TRUE(none.empty());
    float x, y;
    EXPECT_EQ(none.draw(0.25f, 0.75f, x, y), 1.0f);
    EXPECT_EQ(x, 0.25f);
    EXPECT_EQ(y, 0.75f);
}

// The room of test_sun_light.cpp (4 x 3 x 4 m, a 1 m^2 window in its ceiling, the camera under
// the ceiling looking down), with bounces, so that photons leave records the camera sees.
SceneDesc room(int max_depth) {
    SceneDesc s = test::box_with_a_window(normalize(Vec3{0.3f, -1, 0.2f}), Vec3{800, 700, 500}, 0.6f);
    s.render.max_depth = max_depth;
    return s;
}

// The same room lit by one lamp instead of the sun.
SceneDesc room_lit_by(const LightDesc& lamp) {
    SceneDesc s = room(3);
    s.lights = {lamp};
    return s;
}

struct Through {
    double fraction = 0, flux = 0, rel_error = 0;
};

Through through_the_window(const LightSet& lights, int n) {
    Rng rng(5, 0);
    Through t;
    int count = 0;
    for (int k = 0; k < n; ++k) {
        const EmittedPhoton e = lights.emit(rng);
        const float s = (3 - e.origin.y) / e.direction.y;
        const Vec3 x = e.origin + e.direction * s;
        if (!(s > 0) || x.x < 1.5f || x.x > 2.5f || x.z < 1.5f || x.z > 2.5f) continue;
        ++count;
        t.flux += average(e.flux) / n;
    }
    t.fraction = static_cast<double>(count) / n;
    t.rel_error = 1 / std::sqrt(std::max(count, 1));
    return t;
}

// Light 0's photons through the window, aimed (as the context has it) and then unaimed: both
// carry `want` W through it, and aimed at least `gain` times as many of them cross it.
void expect_more_photons_with_the_same_flux(RenderContext& ctx, double want, double gain, const char* what) {
    const int n = 200000;
    const Through aimed = through_the_window(ctx.lights, n);
    ctx.lights.aim(0, EmissionAim{});
    const Through plain = through_the_window(ctx.lights, n);
    std::printf("%s through the window: aimed %.4f of the photons, %.3f W; unaimed %.4f, %.3f W; want %.3f W\n", what,
                aimed.fraction, aimed.flux, plain.fraction, plain.flux, want);
    EXPECT_NEAR(plain.flux, want, 4 * plain.rel_error * want);
    // An aimed photon's flux varies with its cell (the cells at the window's border are drawn
    // less often than its middle): a looser bound than the count's alone.
    EXPECT_NEAR(aimed.flux, want, 8 * aimed.rel_error * want);
    EXPECT_GT(aimed.fraction, gain * plain.fraction) << "aimed photons mostly cross the window";
}

TEST(EmissionAim, AimedSunPhotonsCrossTheWindowAndCarryItsFlux) {
    RenderContext ctx(room(3));
    ASSERT_EQ(ctx.lights.count(), 1u);
    ASSERT_FALSE(ctx.lights.aim_of(0).empty()) << "the pilot found photons the camera sees";
    const Vec3 d = normalize(Vec3{0.3f, -1, 0.2f});
    const double want = average(Vec3{800, 700, 500}) * -d.y * 1.0;  // E |d.y| x 1 m^2
    expect_more_photons_with_the_same_flux(ctx, want, 5, "sun");
}

// Without bounces no photon is stored (direct light is the camera pass's), so nothing is aimed.
TEST(EmissionAim, NothingToAimWhenThePhotonsStoreNothing) {
    const RenderContext ctx(room(1));
    EXPECT_TRUE(ctx.lights.aim_of(0).empty());
}

// Rendered, aimed or not: the same room, with less noise from seed to seed (4 seeds each) where
// the floor is lit only by light off the walls (the photons'; the sun's patch, direct light, is
// left out: its border pixels' noise is the pixel's own area sampled pass by pass).
TEST(EmissionAim, TheRoomIsTheSameAimedAndLessNoisy) {
    SceneDesc s = room(3);
    s.render.passes = 16;
    s.render.photons_per_pass = 20000;
    double mean[2] = {0, 0}, noise[2] = {0, 0};
    for (int aimed = 0; aimed < 2; ++aimed) {
        std::vector<float> img[4];
        for (int seed = 1; seed <= 4; ++seed) {
            s.render.seed = static_cast<uint64_t>(seed);
            img[seed - 1] = test::render_switched(s, [aimed](RenderContext& ctx) {
                                if (!aimed) ctx.lights.aim(0, EmissionAim{});
                            }).steady;
        }
        double sum = 0, diff2 = 0;
        int pixels = 0;
        for (int pair = 0; pair < 2; ++pair)
            for (size_t p = 0; p + 2 < img[0].size(); p += 3) {
                const std::vector<float>&A = img[2 * pair], &B = img[2 * pair + 1];
                const double a = (A[p] + A[p + 1] + A[p + 2]) / 3.0, b = (B[p] + B[p + 1] + B[p + 2]) / 3.0;
                if (a > 5 || b > 5) continue;  // the patch and its border (the patch: ~120)
                sum += 0.5 * (a + b);
                diff2 += 0.5 * (a - b) * (a - b);
                ++pixels;
            }
        ASSERT_GT(pixels, 4000);
        mean[aimed] = sum / pixels;
        noise[aimed] = std::sqrt(diff2 / pixels) / mean[aimed];
    }
    std::printf("room: mean %.5f aimed, %.5f not (ratio %.4f); per-pixel noise %.4f aimed, %.4f not\n", mean[1],
                mean[0], mean[1] / mean[0], noise[1], noise[0]);
    EXPECT_NEAR(mean[1] / mean[0], 1.0, 0.02);
    EXPECT_LT(noise[1], 0.55 * noise[0]);
}

// A 20 cm square lamp 2 m above the window, facing down: most of its photons land on the roof.
// Aimed, its photons cross the window far more often, with the same flux through it; the
// flux through the window is also computed independently, by quadrature over the lamp and the
// window (L cos cos / d^2).
TEST(EmissionAim, AimedLampPhotonsCrossTheWindowAndCarryItsFlux) {
    LightDesc lamp;
    lamp.type = LightType::Quad;
    lamp.corner = {1.9f, 5, 1.9f};
    lamp.edge1 = {0.2f, 0, 0};  // edge1 x edge2 faces down
    lamp.edge2 = {0, 0, 0.2f};
    lamp.radiance = Vec3(1000);
    RenderContext ctx(room_lit_by(lamp));
    ASSERT_FALSE(ctx.lights.aim_of(0).empty());
    // Quadrature: 8 x 8 points on the lamp, 64 x 64 on the window, both facing each other.
    double want = 0;
    for (int a = 0; a < 64; ++a)
        for (int b = 0; b < 64 * 64; ++b) {
            const float ax = (static_cast<float>(a % 8) + 0.5f) / 8, az = (static_cast<float>(a / 8) + 0.5f) / 8;
            const float bx = (static_cast<float>(b % 64) + 0.5f) / 64, bz = (static_cast<float>(b / 64) + 0.5f) / 64;
            const Vec3 x{1.9f + 0.2f * ax, 5, 1.9f + 0.2f * az}, y{1.5f + bx, 3, 1.5f + bz};
            const Vec3 v = y - x;
            const double d2 = dot(v, v), c = 2.0 / std::sqrt(d2);  // both cosines: the drop of 2 m over the distance
            want += 1000.0 * c * c / d2 * (0.04 / 64) * (1.0 / 4096);
        }
    expect_more_photons_with_the_same_flux(ctx, want, 3, "lamp");
}

// A lamp inside the room it lights, under the ceiling: nearly every direction lands where the
// camera sees, aiming would gain nothing, and its photons stay as they were.
TEST(EmissionAim, ALampInsideTheRoomIsLeftAsItWas) {
    LightDesc lamp;
    lamp.type = LightType::Point;
    lamp.position = {1, 2, 1};
    lamp.power = Vec3(100);
    const RenderContext ctx(room_lit_by(lamp));
    const std::vector<double> u = light_usefulness(ctx, 0);
    std::printf("lamp inside: gain %.3f\n", aim_gain(u, kAimFloor));
    EXPECT_LT(aim_gain(u, kAimFloor), kAimMinGain);
    EXPECT_TRUE(ctx.lights.aim_of(0).empty());
}


// Many lamps above the window: only the kAimMostLights most powerful are tried (the pilot's cost
// stays bounded), and they are aimed.
TEST(EmissionAim, OnlyTheMostPowerfulLightsAreTried) {
    SceneDesc s = room(3);
    s.lights.clear();
    for (int k = 0; k < 10; ++k) {
        LightDesc lamp;
        lamp.type = LightType::Point;
        lamp.position = {1.6f + 0.08f * static_cast<float>(k), 5, 2};
        lamp.power = Vec3(10.0f + static_cast<float>(k));  // the last ones the most powerful
        s.lights.push_back(lamp);
    }
    const RenderContext ctx(s);
    size_t aimed = 0;
    for (size_t i = 0; i < ctx.lights.count(); ++i) {
        aimed += !ctx.lights.aim_of(i).empty();
        if (i + kAimMostLights < ctx.lights.count()) EXPECT_TRUE(ctx.lights.aim_of(i).empty()) << "lamp " << i;
    }
    EXPECT_EQ(aimed, kAimMostLights);
}


// The pilot has a seed of its own and each cell its own random stream: the same figures for any
// seed of the render and any number of threads (ranks, sections and resume build it alike).
TEST(EmissionAim, ThePilotIsTheSameForAnySeedAndThreadCount) {
    SceneDesc s = room(3);
    const std::vector<double> u = light_usefulness(RenderContext(s), 0);
    s.render.seed = 99;
    std::vector<double> one;
    {
        tbb::global_control only(tbb::global_control::max_allowed_parallelism, 1);
        one = light_usefulness(RenderContext(s), 0);
    }
    EXPECT_EQ(u, one);
}


// The room and its haze seen from 3000 km away (a float step along the camera's ray would add
// nothing there): the pilot ends, and aims the sun as it does from inside.
TEST(EmissionAim, ThePilotEndsForACameraFarAway) {
    SceneDesc s = room(3);
    s.medium.present = true;
    s.medium.sigma_s = Vec3(0.05f);
    s.medium.sigma_a = Vec3(0.01f);
    s.camera.position = {2, 3e6f, 2};
    s.camera.vfov_deg = 0.0001f;
    const RenderContext ctx(s);
    EXPECT_EQ(light_usefulness(ctx, 0).size(), static_cast<size_t>(kAimCells) * kAimCells);
}

}  // namespace
}  // namespace sl
