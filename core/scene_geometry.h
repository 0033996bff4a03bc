#pragma once
// The scene's surfaces in an Embree BVH, with what the renderer needs at a hit: the material
// and, for a quad light's own surface, which light it is.
#include <embree3/rtcore.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "config/scene_desc.h"
#include "core/import/mesh_data.h"
#include "core/import/mesh_instances.h"

namespace sl {

struct SurfaceHit {
    float t = 0;
    Vec3 position;
    Vec3 normal;      // unit geometric normal (not oriented)
    // Unit shading normal: interpolated from an imported mesh's vertex normals, else the
    // geometric one; on the same side as `normal`. Scattering and gathering use it; ray
    // offsets and side tests use the geometric normal.
    Vec3 shading_normal;
    Vec3 front;         // the counter-clockwise face's side (+-normal): an emitter's front
    float tex_u = 0, tex_v = 0;  // texture coordinates, when the mesh has them
    // Normal-mapped meshes only (MeshData::tangent_frames): the unit tangent (along +u) and the
    // handedness of the bitangent cross(shading_normal, tangent) * tangent_sign, which points
    // "up" the image (-v); 0 when there is no frame (no UVs, or degenerate ones).
    Vec3 tangent;
    float tangent_sign = 0;
    int material = -1;  // index into SceneDesc::materials; -1 for a light's surface
    int light = -1;     // index into SceneDesc::lights when the surface is a quad light
};

// An instance's transform into the scene, and its normals' (SceneGeometry's hits and point queries).
struct InstancePlacement {
    Affine to_scene;
    NormalMatrix normals;
};

class SceneGeometry {
public:
    explicit SceneGeometry(const SceneDesc& scene);
    ~SceneGeometry();
    SceneGeometry(const SceneGeometry&) = delete;
    SceneGeometry& operator=(const SceneGeometry&) = delete;

    // Closest hit along o + t d for t in (tnear, tfar); false on a miss.
    bool intersect(Vec3 o, Vec3 d, float tnear, float tfar, SurfaceHit& hit) const;
    // True when anything blocks o + t d for t in (tnear, tfar).
    bool occluded(Vec3 o, Vec3 d, float tnear, float tfar) const;
    // True when anything blocks the way from `origin` (a point lifted off its surface, ray_epsilon)
    // to `target` (a point on a light): aimed from the origin itself and stopped 1e-4 of that
    // length short of the target, so that the light's own surface is never met. Measured from the
    // unlifted point instead, the lift (about 2e-5 m three metres from the camera) outgrew the
    // margin on every surface parallel to a quad lamp within about 0.2 m of it, whatever the
    // angle, and all its direct light was lost (a floor under a low lamp rendered black).
    bool occluded_to(Vec3 origin, Vec3 target) const {
        const Vec3 v = target - origin;
        const float len = length(v);
        if (!(len > 0)) return false;
        return occluded(origin, v / len, 0, len * (1 - 1e-4f));
    }
    // The distance from c to the nearest surface reaching higher than `height` above the plane
    // through p with unit normal n, or `radius` when there is none nearer: no ray from c of
    // length below it that stays above that height can hit anything. One BVH traversal (a point
    // query); conservative: a triangle counts if one of its corners is above the height, a
    // sphere always. (The gather's blockers skip their rays on open ground with it.)
    float clear_radius(Vec3 c, float radius, Vec3 p, Vec3 n, float height) const;
    // Distinct for every SceneGeometry made in the process (a cache's key).
    uint64_t id() const { return id_; }

    Vec3 bounds_min() const { return bmin_; }
    Vec3 bounds_max() const { return bmax_; }
    size_t triangle_count() const { return triangles_; }

private:
    void build(const SceneDesc& desc);
    void add_triangles(const std::vector<Vec3>& v, const std::vector<uint32_t>& idx, int material, int light,
                       std::shared_ptr<const MeshData> mesh = nullptr);
    void add_sphere(Vec3 center, float radius, int material);
    // A mesh placed by instances: built once in a scene of its own, then one instance per copy.
    void add_instances(const InstancedMesh& im);
    RTCScene prototype(const MeshData& m);
    // Commits g, attaches it to the scene and records what its hits mean (by its Embree ID).
    unsigned attach(RTCGeometry g, int material, int light, std::shared_ptr<const MeshData> mesh,
                const float* vertices = nullptr, const uint32_t* indices = nullptr);

    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::vector<int> geom_material_, geom_light_;  // by Embree geometry ID
    std::vector<std::shared_ptr<const MeshData>> geom_mesh_;  // imported meshes: per-triangle data
    // By Embree geometry ID, for point queries: a triangle mesh's vertex (xyz) and index buffers
    // (owned by Embree), null for a sphere.
    std::vector<const float*> geom_vertices_;
    std::vector<const uint32_t*> geom_indices_;
    std::vector<const float*> spheres_;  // each sphere's centre and radius (owned by Embree)
    // Instances: by the top-level Embree geometry ID, the placement (null for other geometry);
    // hits inside one report the instance's ID in instID[0] and the prototype's in geomID.
    std::vector<const InstancePlacement*> geom_placed_;
    std::vector<std::unique_ptr<InstancePlacement>> placed_;
    struct Prototype {
        RTCScene scene;
        const float* vertices;
        const uint32_t* indices;
    };
    std::vector<std::pair<const MeshData*, Prototype>> prototypes_;
    uint64_t id_;
    Vec3 bmin_{1e30f}, bmax_{-1e30f};
    size_t triangles_ = 0;
};

// Offset that lifts a ray origin off the surface it leaves (scales with the coordinates).
inline float ray_epsilon(Vec3 p, float t) {
    float m = std::max(std::max(std::abs(p.x), std::abs(p.y)), std::max(std::abs(p.z), t));
    return 64.0f * 1.1920929e-7f * std::max(m, 1e-3f);
}

}  // namespace sl
