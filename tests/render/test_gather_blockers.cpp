// The gather's blockers against geometry worked out by hand: a point on a floor at distance D
// from a wall standing on it keeps the disc less the circular segment beyond the wall and the
// one beyond its mirror line (at max(D, R/4) on the other side), a segment at distance d being
// R^2 acos(d/R) - d sqrt(R^2 - d^2), whatever the wall's direction against the point's tangent
// frame, and keeps exactly the photons in between; a point inside a large sphere (a concave
// surface) and one on an open floor keep the whole disc.
#include <gtest/gtest.h>

#include <cmath>

#include "render_helpers.h"
#include "scenes_for_tests.h"
#include "stages/render/gather_blockers.h"

namespace sl {
namespace {

constexpr double kPiD = 3.14159265358979;

SceneDesc floor_and_wall(float angle) {  // the wall through the origin, turned by `angle` about y
    SceneDesc s;
    s.source = "<test blockers>";
    s.camera.position = {0, 3, 0.01f};
    s.camera.look_at = {0, 0, 0};
    MaterialDesc grey;
    grey.name = "grey";
    grey.albedo = Vec3(0.5f);
    s.materials.push_back(grey);
    s.shapes.push_back(test::quad({-5, 0, 5}, {10, 0, 0}, {0, 0, -10}));
    const Vec3 along{std::sin(angle), 0, std::cos(angle)};
    s.shapes.push_back(test::quad(along * -5.0f, along * 10.0f, {0, 1, 0}));
    LightDesc l;
    l.type = LightType::Point;
    l.position = {0.5f, 2, 0};
    l.power = Vec3(1);
    s.lights.push_back(l);
    return s;
}

TEST(GatherBlockers, APointBesideAWallKeepsTheDiscLessTheSegmentBeyondIt) {
    const float R = 0.1f;
    for (float angle : {0.0f, 0.2f, 0.7853982f, 1.1f}) {
        RenderContext ctx(floor_and_wall(angle));
        const Vec3 normal_of_wall{std::cos(angle), 0, -std::sin(angle)};  // horizontal, across the wall
        for (double D : {0.0005, 0.03, 0.07, 0.099, 0.15}) {
            SCOPED_TRACE(::testing::Message() << "wall at " << angle << " rad, D = " << D);
            const Vec3 p = normal_of_wall * static_cast<float>(D);
            GatherBlockers b(ctx.geometry, p, {0, 1, 0}, R * R);
            auto segment = [R](double d) { return d >= R ? 0.0 : R * R * std::acos(d / R) - d * std::sqrt(R * R - d * d); };
            const double mirror = std::max(D, 0.25 * R);
            const double want = kPiD * R * R - segment(D) - segment(mirror);
            EXPECT_NEAR(b.area(), want, 0.004 * kPiD * R * R);
            // Photons on the floor: on the point's side kept, beyond the wall not.
            for (float s : {-0.9f, -0.4f, 0.0f, 0.4f, 0.9f}) {
                const Vec3 along{std::sin(angle), 0, std::cos(angle)};
                const Vec3 mine = normal_of_wall * 0.001f + along * (s * R);
                const Vec3 beyond = normal_of_wall * -0.001f + along * (s * R);
                if (dot(mine - p, mine - p) < R * R) EXPECT_TRUE(b.visible(mine)) << s;
                if (D < R && dot(beyond - p, beyond - p) < R * R) EXPECT_FALSE(b.visible(beyond)) << s;
                // Past the mirror line, on the point's own side: left out too.
                const Vec3 past = p + normal_of_wall * static_cast<float>(mirror + 0.002) + along * (s * 0.3f * R);
                if (D < R && dot(past - p, past - p) < R * R) EXPECT_FALSE(b.visible(past)) << s;
                const Vec3 within = p + normal_of_wall * static_cast<float>(mirror - 0.002) + along * (s * 0.3f * R);
                if (D < R && D > 0.003 && dot(within - p, within - p) < R * R) EXPECT_TRUE(b.visible(within)) << s;
            }
        }
    }
}

TEST(GatherBlockers, ConcaveAndOpenSurfacesKeepTheWholeDisc) {
    SceneDesc s = floor_and_wall(0);
    ShapeDesc sphere;
    sphere.type = ShapeType::Sphere;
    sphere.center = {20, 0, 0};
    sphere.radius = 1;  // the inside of a sphere of radius 10 R at its bottom
    s.shapes.push_back(sphere);
    RenderContext ctx(s);
    const float R = 0.1f;
    GatherBlockers open(ctx.geometry, {2, 0, 2}, {0, 1, 0}, R * R);
    EXPECT_FALSE(open.any());
    EXPECT_NEAR(open.area(), kPiD * R * R, 1e-6 * kPiD * R * R);  // float R^2
    GatherBlockers inside(ctx.geometry, {20, -1, 0}, {0, 1, 0}, R * R);  // the sphere's bottom, inside
    EXPECT_FALSE(inside.any());
    EXPECT_NEAR(inside.area(), kPiD * R * R, 1e-6 * kPiD * R * R);
}

}  // namespace
}  // namespace sl
