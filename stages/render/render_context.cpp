#include "stages/render/render_context.h"

#include <algorithm>
#include <cmath>

#include <stdexcept>

#include "stages/render/edge_radius.h"
#include "stages/render/photon_map.h"
#include "stages/render/emission_aim_pilot.h"

namespace sl {

namespace {
// The scene's extent for lights that cover it (a sun): the surfaces and the medium's box.
Vec3 extent_min(const SceneDesc& d, const SceneGeometry& g) {
    return d.medium.present && d.medium.has_bounds ? vmin(g.bounds_min(), d.medium.bounds_min) : g.bounds_min();
}
Vec3 extent_max(const SceneDesc& d, const SceneGeometry& g) {
    return d.medium.present && d.medium.has_bounds ? vmax(g.bounds_max(), d.medium.bounds_max) : g.bounds_max();
}
}  // namespace

namespace {
// Files are read once, by resolve_imports, before anything is built from them.
const SceneDesc& resolved(const SceneDesc& desc) {
    for (const ShapeDesc& s : desc.shapes)
        if ((s.type == ShapeType::Mesh || s.type == ShapeType::Gltf) && !s.mesh)
            throw std::logic_error("RenderContext: " + s.file + " was not imported (call resolve_imports first)");
    return desc;
}
}  // namespace

RenderContext::RenderContext(const SceneDesc& desc)
    : scene(resolved(desc)), render(desc.render), emission(desc.emission.mode), geometry(scene), lights(scene, extent_min(scene, geometry), extent_max(scene, geometry)),
      materials(scene), camera(desc.camera) {
    timeline = timeline_of(desc);
    width = desc.camera.width;
    height = desc.camera.height;
    automatic_radius_ = !(desc.render.radius > 0);
    initial_radius = automatic_radius_ ? choose_initial_radius(desc, geometry, camera) : desc.render.radius;
    if (desc.medium.present) {
        HomogeneousMedium m(desc.medium, geometry.bounds_min(), geometry.bounds_max());
        if (m.active()) {
            medium.emplace(m);
            volume_radius = choose_volume_radius(desc, m, camera);
            for (const LightDesc& l : desc.lights) {
                if (l.type != LightType::Point && l.type != LightType::Spot) continue;
                float t0, t1;
                if (!m.clip(l.position, Vec3(0, 0, 1), -1e-6f, 1e-6f, t0, t1)) continue;  // outside the box
                float px, py;
                if (camera.project(l.position, px, py) && px > -2 && py > -2 && px < width + 2 && py < height + 2)
                    light_images.push_back({px, py});
            }
        }
    }
    // Before the beam radius's pilot, which counts the volume photons of aimed lights.
    if (aim_photons) aim_lights(*this);
    if (medium && automatic_radius_) volume_radius = widened_for_sparse_photons(volume_radius, *medium);
}

float RenderContext::widened_for_sparse_photons(float r, const HomogeneousMedium& m) {
    if (render.photons_per_pass <= 0) return r;
    // The pilot: its own seed, so that every seed of a scene gets the same radius.
    const uint64_t seed = render.seed;
    render.seed = kPilotSeed;
    const double per_pass = pilot_yield(*this, kVolumePilotPaths).volume_per_path *
                            static_cast<double>(render.photons_per_pass);
    render.seed = seed;
    const Vec3 e = m.box_max() - m.box_min();
    const double volume = static_cast<double>(e.x) * e.y * e.z, across = 0.5 * length(e);
    if (!(per_pass > 0) || !(volume > 0) || !(across > 0)) return r;
    const double wanted = std::sqrt(kBeamPhotons * volume / (per_pass * kPiDouble * across));
    return std::max(r, std::min(static_cast<float>(wanted), std::min(4 * r, 0.05f * length(e))));
}

const GatherRadii& RenderContext::gather_radii() const {
    std::call_once(radii_once_, [this] {
        if (automatic_radius_) gather_radii_ = edge_aware_radii(geometry, camera, width, height, initial_radius);
    });
    return gather_radii_;
}

float choose_initial_radius(const SceneDesc& desc, const SceneGeometry& geometry, const PinholeCamera& camera) {
    Vec3 lo = geometry.bounds_min(), hi = geometry.bounds_max();
    float diag = length(hi - lo);
    if (!(diag > 0)) return 0.01f;
    float dist = std::max(length((lo + hi) * 0.5f - camera.position()), 1e-6f * diag);
    float r = 3.0f * pulse_radius_factor(desc) * camera.pixel_footprint(dist);
    return std::clamp(r, 1e-5f * diag, 0.05f * diag);
}

float pulse_radius_factor(const SceneDesc& desc) {
    if (desc.emission.mode != EmissionMode::Pulse) return 1.0f;
    const double slices = static_cast<double>(desc.time.frames) / std::max(desc.emission.width_frames, 1);
    return static_cast<float>(std::clamp(std::pow(slices, 1.0 / 6.0), 1.0, 2.0));
}

float choose_volume_radius(const SceneDesc& desc, const HomogeneousMedium& medium, const PinholeCamera& camera) {
    if (desc.render.radius > 0) return desc.render.radius;
    Vec3 lo = medium.box_min(), hi = medium.box_max();
    float diag = length(hi - lo);
    float dist = std::max(length((lo + hi) * 0.5f - camera.position()), 0.1f * diag);
    float r = 3.0f * camera.pixel_footprint(dist);
    return std::clamp(r, 1e-5f * diag, 0.05f * diag);
}

}  // namespace sl
