#include "core/scene_geometry.h"

#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>

#include "foundation/errors.h"
#include "core/shape_triangles.h"

namespace sl {
namespace {

void embree_error(void*, RTCError code, const char* str) {
    // Errors are turned into exceptions where the call returns; this only keeps Embree quiet.
    (void)code;
    (void)str;
}

// A hit's tangent frame on a normal-mapped mesh: glTF's TANGENT interpolated when the file
// has it; otherwise per triangle from its UV derivatives, the tangent dp/du and the handedness
// that makes the bitangent -dp/dv (glTF's v runs down the image and a normal map's +y is up).
// MikkTSpace, which glTF names, averages these per-triangle frames over the faces that share a
// vertex: on a flat or UV-continuous surface the two are the same direction.
void tangent_frame(const MeshData& m, const uint32_t* tri, float bu, float bv, float bw, SurfaceHit& hit) {
    if (!m.tangents.empty()) {
        const float *t0 = &m.tangents[4 * tri[0]], *t1 = &m.tangents[4 * tri[1]], *t2 = &m.tangents[4 * tri[2]];
        const Vec3 t = Vec3(t0[0], t0[1], t0[2]) * bw + Vec3(t1[0], t1[1], t1[2]) * bu + Vec3(t2[0], t2[1], t2[2]) * bv;
        const float l = length(t);
        if (l > 0 && std::isfinite(l)) {
            hit.tangent = t / l;
            hit.tangent_sign = t0[3] < 0 ? -1.0f : 1.0f;
            return;
        }  // (a primitive without TANGENT among ones with: from its UVs)
    }
    const Vec3 p0 = m.positions[tri[0]], e1 = m.positions[tri[1]] - p0, e2 = m.positions[tri[2]] - p0;
    const float* uv = m.uvs.data();
    const float du1 = uv[2 * tri[1]] - uv[2 * tri[0]], dv1 = uv[2 * tri[1] + 1] - uv[2 * tri[0] + 1];
    const float du2 = uv[2 * tri[2]] - uv[2 * tri[0]], dv2 = uv[2 * tri[2] + 1] - uv[2 * tri[0] + 1];
    const float det = du1 * dv2 - du2 * dv1;
    if (!(std::abs(det) > 0)) return;  // degenerate UVs: no frame, the map is not applied
    const Vec3 dpdu = (e1 * dv2 - e2 * dv1) / det, dpdv = (e2 * du1 - e1 * du2) / det;
    const float l = length(dpdu);
    if (!(l > 0) || !std::isfinite(l)) return;
    hit.tangent = dpdu / l;
    hit.tangent_sign = dot(cross(hit.shading_normal, hit.tangent), dpdv) > 0 ? -1.0f : 1.0f;
}

}  // namespace

SceneGeometry::SceneGeometry(const SceneDesc& desc) {
    static std::atomic<uint64_t> made{0};
    id_ = ++made;
    device_ = rtcNewDevice("threads=0");
    if (!device_) throw RuntimeFailure("cannot create the Embree device (error " +
                                       std::to_string(rtcGetDeviceError(nullptr)) + ")");
    rtcSetDeviceErrorFunction(device_, embree_error, nullptr);
    try {
        build(desc);
    } catch (...) {  // the destructor does not run for a half-built object: release here
        if (scene_) rtcReleaseScene(scene_);
        for (auto& p : prototypes_) rtcReleaseScene(p.second.scene);
        rtcReleaseDevice(device_);
        throw;
    }
}

void SceneGeometry::build(const SceneDesc& desc) {
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);

    for (const ShapeDesc& s : desc.shapes) {
        if (s.type == ShapeType::Sphere) {
            add_sphere(s.center, s.radius, s.material);
        } else if (s.mesh) {  // imported (core/import/resolve_imports.h): already in scene space
            // (Empty when all of it is placed by instances: Embree takes no empty buffer.)
            if (!s.mesh->indices.empty()) add_triangles(s.mesh->positions, s.mesh->indices, -1, -1, s.mesh);
            if (s.instances)
                for (const InstancedMesh& im : s.instances->meshes) add_instances(im);
        } else {
            TriangleSoup soup = triangulate_shape(s);
            add_triangles(soup.vertices, soup.indices, s.material, -1);
        }
    }
    // Quad lights are surfaces too: the camera sees their front, photons stop on them.
    for (size_t i = 0; i < desc.lights.size(); ++i) {
        const LightDesc& l = desc.lights[i];
        if (l.type != LightType::Quad) continue;
        std::vector<Vec3> v{l.corner, l.corner + l.edge1, l.corner + l.edge1 + l.edge2, l.corner + l.edge2};
        add_triangles(v, {0, 1, 2, 0, 2, 3}, -1, static_cast<int>(i));
    }
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE)
        throw RuntimeFailure("Embree could not build the scene");
    if (bmin_.x > bmax_.x) bmin_ = bmax_ = Vec3(0);
}

SceneGeometry::~SceneGeometry() {
    if (scene_) rtcReleaseScene(scene_);
    for (auto& p : prototypes_) rtcReleaseScene(p.second.scene);
    if (device_) rtcReleaseDevice(device_);
}

void SceneGeometry::add_triangles(const std::vector<Vec3>& v, const std::vector<uint32_t>& idx,
                                  int material, int light, std::shared_ptr<const MeshData> mesh) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                           RTC_FORMAT_FLOAT3, 3 * sizeof(float), v.size()));
    auto* ib = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0,
                                                              RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), idx.size() / 3));
    if (!vb || !ib) throw RuntimeFailure("Embree could not allocate a mesh buffer");
    for (size_t i = 0; i < v.size(); ++i) {
        vb[3 * i] = v[i].x; vb[3 * i + 1] = v[i].y; vb[3 * i + 2] = v[i].z;
        bmin_ = vmin(bmin_, v[i]);
        bmax_ = vmax(bmax_, v[i]);
    }
    std::memcpy(ib, idx.data(), idx.size() * sizeof(uint32_t));
    attach(g, material, light, std::move(mesh), vb, ib);
    triangles_ += idx.size() / 3;
}

unsigned SceneGeometry::attach(RTCGeometry g, int material, int light, std::shared_ptr<const MeshData> mesh,
                           const float* vertices, const uint32_t* indices) {
    rtcCommitGeometry(g);
    unsigned id = rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
    if (geom_material_.size() <= id) {
        geom_material_.resize(id + 1, -1);
        geom_light_.resize(id + 1, -1);
        geom_mesh_.resize(id + 1);
        geom_vertices_.resize(id + 1, nullptr);
        geom_indices_.resize(id + 1, nullptr);
        geom_placed_.resize(id + 1, nullptr);
    }
    geom_vertices_[id] = vertices;
    geom_indices_[id] = indices;
    geom_material_[id] = material;
    geom_light_[id] = light;
    geom_mesh_[id] = std::move(mesh);
    return id;
}

RTCScene SceneGeometry::prototype(const MeshData& m) {
    for (auto& p : prototypes_)
        if (p.first == &m) return p.second.scene;
    RTCScene proto = rtcNewScene(device_);
    rtcSetSceneFlags(proto, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(proto, RTC_BUILD_QUALITY_HIGH);
    prototypes_.push_back({&m, {proto, nullptr, nullptr}});
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), m.positions.size()));
    auto* ib = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(uint32_t), m.triangle_count()));
    if (!vb || !ib) {
        rtcReleaseGeometry(g);
        throw RuntimeFailure("Embree could not allocate a mesh buffer");
    }
    for (size_t i = 0; i < m.positions.size(); ++i) {
        vb[3 * i] = m.positions[i].x; vb[3 * i + 1] = m.positions[i].y; vb[3 * i + 2] = m.positions[i].z;
    }
    std::memcpy(ib, m.indices.data(), m.indices.size() * sizeof(uint32_t));
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(proto, g, 0);  // the prototype's only geometry: geomID 0 in every hit
    rtcReleaseGeometry(g);
    rtcCommitScene(proto);
    prototypes_.back().second.vertices = vb;
    prototypes_.back().second.indices = ib;
    return proto;
}

void SceneGeometry::add_instances(const InstancedMesh& im) {
    const MeshData& m = *im.mesh;
    RTCScene proto = prototype(m);
    const Prototype* pr = nullptr;
    for (auto& p : prototypes_)
        if (p.first == &m) pr = &p.second;
    for (const Affine& a : im.placements) {
        RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(g, proto);
        rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, a.m);
        placed_.push_back(std::make_unique<InstancePlacement>(InstancePlacement{a, NormalMatrix(a)}));
        geom_placed_[attach(g, -1, -1, im.mesh, pr->vertices, pr->indices)] = placed_.back().get();
        for (Vec3 p : m.positions) {  // the placed vertices' box, as for a mesh in scene space
            const Vec3 w = a.point(p);
            bmin_ = vmin(bmin_, w);
            bmax_ = vmax(bmax_, w);
        }
        triangles_ += m.triangle_count();
    }
}

void SceneGeometry::add_sphere(Vec3 c, float r, int material) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                           RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
    if (!vb) throw RuntimeFailure("Embree could not allocate a sphere buffer");
    vb[0] = c.x; vb[1] = c.y; vb[2] = c.z; vb[3] = r;
    attach(g, material, -1, nullptr);
    spheres_.push_back(vb);
    bmin_ = vmin(bmin_, c - Vec3(r));
    bmax_ = vmax(bmax_, c + Vec3(r));
}

bool SceneGeometry::intersect(Vec3 o, Vec3 d, float tnear, float tfar, SurfaceHit& hit) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray.org_x = o.x; rh.ray.org_y = o.y; rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x; rh.ray.dir_y = d.y; rh.ray.dir_z = d.z;
    rh.ray.tnear = tnear;
    rh.ray.tfar = tfar;
    rh.ray.mask = 0xffffffffu;
    rh.ray.flags = 0;
    rh.ray.time = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    // Inside an instance, Embree reports the instance (its top-level ID) in instID[0] and Ng in
    // the prototype's space: the normal matrix brings it into the scene's, front included.
    const unsigned id = rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID ? rh.hit.instID[0] : rh.hit.geomID;
    const InstancePlacement* placed = geom_placed_[id];
    hit.t = rh.ray.tfar;
    hit.position = o + d * hit.t;
    const Vec3 ng_local{rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
    Vec3 n = placed ? placed->normals(ng_local) : ng_local;
    float len = length(n);
    hit.normal = len > 0 ? n / len : Vec3(0, 0, 1);
    hit.material = geom_material_[id];
    hit.light = geom_light_[id];
    hit.shading_normal = hit.normal;
    hit.front = hit.normal;  // Embree's Ng is (v1 - v0) x (v2 - v0): the counter-clockwise side
    if (const MeshData* m = geom_mesh_[id].get()) {
        const size_t prim = rh.hit.primID;
        hit.material = m->tri_material[prim];
        const uint32_t* tri = &m->indices[3 * prim];
        const float bu = rh.hit.u, bv = rh.hit.v, bw = 1 - bu - bv;
        Vec3 ns_local = ng_local;  // the shading normal in the mesh's own space (instances' tangent frames)
        if (!m->normals.empty()) {
            Vec3 ns = m->normals[tri[0]] * bw + m->normals[tri[1]] * bu + m->normals[tri[2]] * bv;
            ns_local = dot(ns, ng_local) < 0 ? -ns : ns;
            if (placed) ns = placed->normals(ns);
            float l = length(ns);
            if (l > 0 && std::isfinite(l)) {
                ns = ns / l;
                hit.shading_normal = dot(ns, hit.normal) < 0 ? -ns : ns;
            }
        }
        if (!m->uvs.empty()) {
            const float* uv = m->uvs.data();
            hit.tex_u = uv[2 * tri[0]] * bw + uv[2 * tri[1]] * bu + uv[2 * tri[2]] * bv;
            hit.tex_v = uv[2 * tri[0] + 1] * bw + uv[2 * tri[1] + 1] * bu + uv[2 * tri[2] + 1] * bv;
            if (m->tangent_frames && !placed) tangent_frame(*m, tri, bu, bv, bw, hit);
            if (m->tangent_frames && placed) {
                // Made in the mesh's own space, then placed: the tangent is a surface direction
                // (the placement's linear part), and a mirroring placement flips the handedness.
                SurfaceHit local;
                local.shading_normal = ns_local;
                tangent_frame(*m, tri, bu, bv, bw, local);
                const Vec3 t = placed->to_scene.vector(local.tangent);
                const float l = length(t);
                if (local.tangent_sign != 0 && l > 0 && std::isfinite(l)) {
                    hit.tangent = t / l;
                    hit.tangent_sign = placed->to_scene.det() < 0 ? -local.tangent_sign : local.tangent_sign;
                }
            }
        }
    }
    return true;
}

bool SceneGeometry::occluded(Vec3 o, Vec3 d, float tnear, float tfar) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r;
    r.org_x = o.x; r.org_y = o.y; r.org_z = o.z;
    r.dir_x = d.x; r.dir_y = d.y; r.dir_z = d.z;
    r.tnear = tnear;
    r.tfar = tfar;
    r.mask = 0xffffffffu;
    r.flags = 0;
    r.time = 0;
    rtcOccluded1(scene_, &ctx, &r);
    return r.tfar < 0;  // Embree sets tfar = -inf on a hit
}

}  // namespace sl
