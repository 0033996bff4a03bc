// The gather's blockers against geometry worked out by hand: a point on a floor at distance D
// from a wall standing on it keeps the disc less the circular segment beyond the wall and the
// one beyond its mirror line (at max(D, R/4) on the other side), a segment at distance d being
// R^2 acos(d/R) - d sqrt(R^2 - d^2), whatever the wall's direction against the point's tangent
// frame, and keeps exactly the photons in between; a point inside a large sphere (a concave
// surface) and one on an open floor keep the whole disc. An edge's line cuts the disc the same
// way, alone and beside a wall.
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
                if (dot(mine - p, mine - p) < R * R) { EXPECT_TRUE(b.visible(mine)) << s; }
                if (D < R && dot(beyond - p, beyond - p) < R * R) { EXPECT_FALSE(b.visible(beyond)) << s; }
                // Past the mirror line, on the point's own side: left out too.
                const Vec3 past = p + normal_of_wall * static_cast<float>(mirror + 0.002) + along * (s * 0.3f * R);
                if (D < R && dot(past - p, past - p) < R * R) { EXPECT_FALSE(b.visible(past)) << s; }
                const Vec3 within = p + normal_of_wall * static_cast<float>(mirror - 0.002) + along * (s * 0.3f * R);
                if (D < R && D > 0.003 && dot(within - p, within - p) < R * R) { EXPECT_TRUE(b.visible(within)) << s; }
            }
        }
    }
}

TEST(GatherBlockers, AnEdgeLineCutsTheDiscAsAWallDoesAloneAndBesideOne) {
    // An edge's line (edge_radius.h) on the floor, parallel to the wall, on the point's other
    // side: alone on open floor, the disc less the segment beyond the line and the one beyond its
    // mirror (max(E, R/4) away); beside the wall, the strip between the nearer of each side's
    // line and the other side's mirror, whichever way the two are turned against the tangent frame.
    const float R = 0.1f;
    auto segment = [R](double d) { return d >= R ? 0.0 : R * R * std::acos(d / R) - d * std::sqrt(R * R - d * d); };
    for (float angle : {0.0f, 0.7853982f, 1.1f}) {
        RenderContext ctx(floor_and_wall(angle));
        const Vec3 across_wall{std::cos(angle), 0, -std::sin(angle)};  // from the wall towards the point
        for (double E : {0.003, 0.02, 0.06, 0.15}) {
            // Open floor, far from the wall: only the edge cuts.
            const Vec3 far = across_wall * 2.0f;
            const GatherBlockers::EdgeLine line{across_wall, dot(across_wall, far) + static_cast<float>(E)};
            GatherBlockers open(ctx.geometry, far, {0, 1, 0}, R * R, &line);
            SCOPED_TRACE(::testing::Message() << "turned " << angle << ", edge at " << E);
            ASSERT_TRUE(open.edge_cut());
            EXPECT_FALSE(open.any());
            EXPECT_NEAR(open.area(), kPiD * R * R - segment(E) - segment(std::max(E, 0.25 * R)), 1e-4 * kPiD * R * R);
            EXPECT_FALSE(open.visible(far + across_wall * static_cast<float>(E + 0.002)));
            EXPECT_TRUE(open.visible(far + across_wall * static_cast<float>(E - 0.002)));
            // Beside the wall, D from it: the wall's side and the edge's side, each cut at the
            // nearer of its own line and the other's mirror.
            for (double D : {0.01, 0.05}) {
                const Vec3 p = across_wall * static_cast<float>(D);
                const GatherBlockers::EdgeLine near_line{across_wall, dot(across_wall, p) + static_cast<float>(E)};
                GatherBlockers b(ctx.geometry, p, {0, 1, 0}, R * R, &near_line);
                ASSERT_TRUE(b.any() && b.edge_cut());
                const double wall_side = std::min(D, std::max(E, 0.25 * R)), edge_side = std::min(E, std::max(D, 0.25 * R));
                EXPECT_NEAR(b.area(), kPiD * R * R - segment(wall_side) - segment(edge_side), 0.004 * kPiD * R * R) << D;
                EXPECT_FALSE(b.visible(p + across_wall * static_cast<float>(edge_side + 0.002))) << D;
                EXPECT_FALSE(b.visible(p - across_wall * static_cast<float>(wall_side + 0.002))) << D;
                EXPECT_TRUE(b.visible(p + across_wall * static_cast<float>(0.5 * (edge_side - wall_side)))) << D;
            }
        }
        // A point on or past the line: no cut (the caller's shrunk disc serves it).
        const Vec3 far = across_wall * 2.0f;
        const GatherBlockers::EdgeLine behind{across_wall, dot(across_wall, far) - 0.01f};
        EXPECT_FALSE(GatherBlockers(ctx.geometry, far, {0, 1, 0}, R * R, &behind).edge_cut());
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

// The blockers skip their rays where a point query finds no surface within their reach rising
// above their start (SceneGeometry::clear_radius). Checked against rays cast by hand: wherever
// the query says nothing rises, fans of rising rays (the blockers' 1 in 2 and others) from the
// lifted point hit nothing; and the query does answer "nothing" on open ground and "something"
// beside the wall, a sphere and a leaning sheet, so the shortcut is taken and is the rays' answer.
TEST(GatherBlockers, ThePointQueryAgreesWithRaysCastByHand) {
    SceneDesc s = floor_and_wall(0.3f);
    ShapeDesc ball;
    ball.type = ShapeType::Sphere;
    ball.center = {2, 0.5f, 1};
    ball.radius = 0.5f;
    s.shapes.push_back(ball);
    s.shapes.push_back(test::quad({-3, 0.02f, -2}, {1, 0, 0}, {0.3f, 1, 0.2f}));  // a sheet leaning over
    RenderContext ctx(s);
    const Vec3 n{0, 1, 0};
    int clear = 0, near = 0;
    for (float R : {0.05f, 0.3f}) {
        const float lift = 1e-3f * R, reach = 1.5f * R / 0.894427191f;
        for (float x = -4.5f; x <= 4.5f; x += 0.23f) {
            for (float z = -4.5f; z <= 4.5f; z += 0.31f) {
                const Vec3 p{x, 0, z}, o = p + n * lift;
                if (ctx.geometry.clear_radius(o, 4 * reach, p, n, 0.5f * lift) <= reach * 1.001f) {
                    ++near;
                    continue;
                }
                ++clear;
                for (int a = 0; a < 64; ++a) {
                    const float phi = a * (6.2831853f / 64);
                    for (float rise : {0.02f, 0.447213595f, 0.9f}) {
                        const Vec3 d = Vec3(std::cos(phi), 0, std::sin(phi)) * std::sqrt(1 - rise * rise) + n * rise;
                        SurfaceHit hit;
                        ASSERT_FALSE(ctx.geometry.intersect(o, d, 0, reach, hit))
                            << "R " << R << " at " << x << ", " << z << ": hit at t " << hit.t;
                    }
                }
                EXPECT_FALSE(GatherBlockers(ctx.geometry, p, n, R * R).any());
            }
        }
        // Beside the wall (through the origin), on the sphere's shoulder zone and under the sheet.
        for (Vec3 p : {Vec3(0.02f, 0, 0.02f), Vec3(2, 0, 1 - 0.5f * std::sqrt(R)), Vec3(-2.5f, 0, -1.97f)}) {
            EXPECT_LT(ctx.geometry.clear_radius(p + n * lift, 4 * reach, p, n, 0.5f * lift), reach) << p.x << ", " << p.z;
        }
    }
    EXPECT_GT(clear, 500);
    EXPECT_GT(near, 50);
}

}  // namespace
}  // namespace sl
