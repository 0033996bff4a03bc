#include "core/import/model_scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "foundation/constants.h"
#include "foundation/errors.h"
#include "core/import/mesh_data.h"
#include "core/import/mesh_instances.h"
#include "core/import/resolve_imports.h"

namespace sl {
namespace fs = std::filesystem;

namespace {
std::string lower_extension(const std::string& path) {
    std::string e = fs::path(path).extension().string();
    for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return e;
}
}  // namespace

bool is_model_file(const std::string& path) {
    const std::string e = lower_extension(path);
    return e == ".glb" || e == ".gltf" || e == ".obj";
}

SceneDesc scene_for_model(const std::string& path, std::optional<LightUnits> light_units, const ImportBudget& budget,
                          std::optional<PrincipledBase> principled) {
    SceneDesc scene;
    scene.source = path;
    ShapeDesc s;
    s.type = lower_extension(path) == ".obj" ? ShapeType::Mesh : ShapeType::Gltf;
    std::error_code ec;
    s.file = fs::absolute(path, ec).lexically_normal().string();
    s.material = -1;
    if (s.type == ShapeType::Gltf) {
        s.light_units = light_units;
        s.principled = principled;
    }
    scene.shapes.push_back(s);
    resolve_imports(scene, budget);

    Vec3 lo(1e30f), hi(-1e30f);
    for (const ShapeDesc& sh : scene.shapes) {
        if (sh.mesh)
            for (Vec3 p : sh.mesh->positions) { lo = vmin(lo, p); hi = vmax(hi, p); }
        if (sh.instances)
            for (const InstancedMesh& im : sh.instances->meshes)
                for (const Affine& a : im.placements)
                    for (Vec3 p : im.mesh->positions) { lo = vmin(lo, a.point(p)); hi = vmax(hi, a.point(p)); }
    }
    for (const LightDesc& l : scene.lights) { lo = vmin(lo, l.position); hi = vmax(hi, l.position); }
    if (lo.x > hi.x) lo = hi = Vec3(0);
    const Vec3 center = (lo + hi) * 0.5f;
    const float diagonal = std::max(length(hi - lo), 1e-3f);

    if (scene.imported_camera) {
        scene.camera = *scene.imported_camera;
    } else {
        CameraDesc& c = scene.camera;
        c.vfov_deg = 40;
        // The bounding sphere fits the view: distance = radius / sin(half the field of view).
        const float radius = 0.5f * diagonal;
        const float dist = radius / std::sin(0.5f * c.vfov_deg * kPi / 180.0f);
        c.look_at = center;
        c.position = center + Vec3(0, 0, dist);
        c.up = {0, 1, 0};
    }
    // Long enough for light to cross the scene three times (and a whole number of ns steps).
    const double crossing_ns = diagonal / kSpeedOfLight;
    scene.time.start_ns = 0;
    scene.time.end_ns = 3 * crossing_ns;
    return scene;
}

}  // namespace sl
