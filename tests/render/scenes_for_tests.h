#pragma once
// Scenes built in code for the renderer's tests, where every number is known.
#include <cmath>
#include <cstdint>

#include "config/scene_desc.h"
#include "config/sun_desc.h"

namespace sl::test {

// A parallelogram corner + u e1 + v e2 (u, v in [0, 1]) of the given material.
inline ShapeDesc quad(Vec3 corner, Vec3 e1, Vec3 e2, int material = 0) {
    ShapeDesc q;
    q.type = ShapeType::Quad;
    q.corner = corner;
    q.edge1 = e1;
    q.edge2 = e2;
    q.material = material;
    return q;
}

// A camera 3 m over the origin looking straight down (image up is -z), seeing +-half_view m
// across res x res pixels, and one grey Lambertian material (index 0) of albedo rho.
inline SceneDesc looking_down_at_grey(const char* source, int res, float half_view, float rho) {
    SceneDesc s;
    s.source = source;
    s.camera.position = {0, 3, 0};
    s.camera.look_at = {0, 0, 0};
    s.camera.up = {0, 0, -1};
    s.camera.vfov_deg = 2 * std::atan(half_view / 3.0f) * 180 / 3.14159265f;
    s.camera.width = s.camera.height = res;
    MaterialDesc grey;
    grey.name = "grey";
    grey.albedo = Vec3(rho);
    s.materials.push_back(grey);
    return s;
}

// A quad lamp corner + u e1 + v e2 of the given radiance, its front edge1 x edge2.
inline LightDesc quad_light(Vec3 corner, Vec3 e1, Vec3 e2, float radiance) {
    return LightDesc{.type = LightType::Quad, .position = {}, .corner = corner, .edge1 = e1, .edge2 = e2,
                     .power = {}, .radiance = Vec3(radiance), .irradiance = {}};
}

// A laser beam of radius `radius` (its flux spread evenly over the disc) from p along unit d.
inline LightDesc laser(Vec3 p, Vec3 d, float radius, float power) {
    LightDesc l;
    l.type = LightType::Laser;
    l.position = p;
    l.direction = d;
    l.radius = radius;
    l.power = Vec3(power);
    return l;
}

// A diffuse plane y = 0 of half-size `half` (albedo rho), a point light of power P at height h
// above the origin, and a camera at height cam_h looking straight down (90 degree field).
inline SceneDesc plane_under_point_light(float rho, float P, float h, float cam_h, int res, float half = 50) {
    SceneDesc s;
    s.source = "<test plane>";
    s.camera.position = {0, cam_h, 0};
    s.camera.look_at = {0, 0, 0};
    s.camera.up = {0, 0, -1};
    s.camera.vfov_deg = 90;
    s.camera.width = s.camera.height = res;
    MaterialDesc m;
    m.name = "grey";
    m.albedo = Vec3(rho);
    s.materials.push_back(m);
    s.shapes.push_back(quad({-half, 0, half}, {2 * half, 0, 0}, {0, 0, -2 * half}));
    LightDesc l;
    l.type = LightType::Point;
    l.position = {0, h, 0};
    l.power = Vec3(P);
    s.lights.push_back(l);
    s.render.max_depth = 1;
    s.render.passes = 4;
    s.render.photons_per_pass = 1000;
    return s;
}

// A closed Cornell-like box (2 m cube) with a quad light under its ceiling.
inline SceneDesc small_box(int res, int passes, int64_t photons, int max_depth = 8) {
    SceneDesc s;
    s.source = "<test box>";
    s.camera.position = {0, 1, 0.99f};
    s.camera.look_at = {0, 1, 0};
    s.camera.vfov_deg = 90;
    s.camera.width = s.camera.height = res;
    MaterialDesc white, red, green;
    white.name = "white"; white.albedo = Vec3(0.7f);
    red.name = "red"; red.albedo = {0.63f, 0.065f, 0.05f};
    green.name = "green"; green.albedo = {0.14f, 0.45f, 0.091f};
    s.materials = {white, red, green};
    s.shapes = {quad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0),   // floor
                quad({-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, 0),   // ceiling
                quad({-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, 0),   // back
                quad({-1, 0, 1}, {2, 0, 0}, {0, 2, 0}, 0),    // front (closes the box behind the camera)
                quad({-1, 0, 1}, {0, 0, -2}, {0, 2, 0}, 1),   // left
                quad({1, 0, -1}, {0, 0, 2}, {0, 2, 0}, 2)};   // right
    LightDesc l;
    l.type = LightType::Quad;
    l.corner = {-0.25f, 1.98f, -0.2f};
    l.edge1 = {0.5f, 0, 0};
    l.edge2 = {0, 0, 0.4f};
    l.radiance = {17, 12, 4};
    s.lights.push_back(l);
    s.time = {0, 24, 12, 24};
    s.render.passes = passes;
    s.render.photons_per_pass = photons;
    s.render.max_depth = max_depth;
    return s;
}

// A closed box x, z in [0, 4], y in [0, 3], with a 1 m x 1 m hole in the ceiling; a camera
// under the ceiling looks straight down at the floor. Direct light only (max_depth 1).
inline SceneDesc box_with_a_window(Vec3 sun_dir, Vec3 E, float rho) {
    SceneDesc s;
    s.source = "<test sun box>";
    s.camera.position = {2, 2.95f, 2};
    s.camera.look_at = {2, 0, 2};
    s.camera.up = {0, 0, -1};
    s.camera.vfov_deg = 70;
    s.camera.width = s.camera.height = 72;
    MaterialDesc floor, wall;
    floor.name = "floor"; floor.albedo = Vec3(rho);
    wall.name = "wall"; wall.albedo = Vec3(0.5f);
    s.materials = {floor, wall};
    s.shapes = {quad({0, 0, 4}, {4, 0, 0}, {0, 0, -4}, 0),        // floor, facing up
                quad({0, 0, 0}, {4, 0, 0}, {0, 3, 0}, 1),         // walls
                quad({0, 0, 4}, {4, 0, 0}, {0, 3, 0}, 1),
                quad({0, 0, 0}, {0, 0, 4}, {0, 3, 0}, 1),
                quad({4, 0, 0}, {0, 0, 4}, {0, 3, 0}, 1),
                // the ceiling around the window x, z in [1.5, 2.5]
                quad({0, 3, 0}, {4, 0, 0}, {0, 0, 1.5f}, 1),
                quad({0, 3, 2.5f}, {4, 0, 0}, {0, 0, 1.5f}, 1),
                quad({0, 3, 1.5f}, {1.5f, 0, 0}, {0, 0, 1}, 1),
                quad({2.5f, 3, 1.5f}, {1.5f, 0, 0}, {0, 0, 1}, 1)};
    s.lights.push_back(make_sun_light(sun_dir, 0.53f, E));
    s.time = {0, 24, 96, 24};  // 0.25 ns (7.5 cm of light) a frame
    s.render.max_depth = 1;
    s.render.passes = 8;
    s.render.photons_per_pass = 2000;
    return s;
}

}  // namespace sl::test
