// SceneGeometry::clear_radius: how far from a point no surface stands above a plane. The gather's blockers (stages/render/gather_blockers.cpp) cast four short rays per
// visible point and pass; on open ground all of them miss, after walking the BVH to its
// leaves. One point query answers for all four: the rays start above the plane and rise, so
// only a surface within their reach that reaches above their start can stop one.
#include <algorithm>
#include <cmath>

#include "core/scene_geometry.h"

namespace sl {
namespace {

struct RiseQuery {
    const std::vector<const float*>* vertices;
    const std::vector<const uint32_t*>* indices;
    const std::vector<const InstancePlacement*>* placed;  // by top-level ID: an instance's transform
    Vec3 c, p, n;
    float height;
};

Vec3 vertex(const float* v, uint32_t i) { return {v[3 * i], v[3 * i + 1], v[3 * i + 2]}; }

// Squared distance from c to triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
float distance2_to_triangle(Vec3 c, Vec3 a, Vec3 b, Vec3 t) {
    const Vec3 ab = b - a, ac = t - a, ap = c - a;
    const float d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return dot(ap, ap);
    const Vec3 bp = c - b;
    const float d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return dot(bp, bp);
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const Vec3 q = a + ab * (d1 / (d1 - d3)) - c;
        return dot(q, q);
    }
    const Vec3 cp = c - t;
    const float d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return dot(cp, cp);
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const Vec3 q = a + ac * (d2 / (d2 - d6)) - c;
        return dot(q, q);
    }
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const Vec3 q = b + (t - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))) - c;
        return dot(q, q);
    }
    const float denom = 1 / (va + vb + vc);
    const Vec3 q = a + ab * (vb * denom) + ac * (vc * denom) - c;
    return dot(q, q);
}

bool rise_callback(RTCPointQueryFunctionArguments* args) {
    auto* q = static_cast<RiseQuery*>(args->userPtr);
    float d2;
    // Inside an instance: its top-level ID, and its triangle brought into the scene's space
    // (the query is the scene's: distances and heights are measured there, whatever the scale).
    const bool inside = args->context->instStackSize > 0;
    const unsigned id = inside ? args->context->instID[0] : args->geomID;
    if (const float* v = (*q->vertices)[id]) {
        const uint32_t* tri = (*q->indices)[id] + 3 * static_cast<size_t>(args->primID);
        Vec3 a = vertex(v, tri[0]), b = vertex(v, tri[1]), t = vertex(v, tri[2]);
        if (const InstancePlacement* pl = inside ? (*q->placed)[id] : nullptr) {
            a = pl->to_scene.point(a);
            b = pl->to_scene.point(b);
            t = pl->to_scene.point(t);
        }
        // The triangle lies in the hull of its corners: none above the height, no part above it.
        const float h = std::max(std::max(dot(a - q->p, q->n), dot(b - q->p, q->n)), dot(t - q->p, q->n));
        if (!(h > q->height)) return false;
        d2 = distance2_to_triangle(q->c, a, b, t);
    } else {
        return false;  // a sphere: Embree's point query does not reach them, clear_radius does
    }
    const float d = std::sqrt(d2);
    if (!(d < args->query->radius)) return false;
    args->query->radius = d;  // only what is nearer matters now: prunes the traversal
    return true;
}

}  // namespace

float SceneGeometry::clear_radius(Vec3 c, float radius, Vec3 p, Vec3 n, float height) const {
    RiseQuery q{&geom_vertices_, &geom_indices_, &geom_placed_, c, p, n, height};
    RTCPointQuery query;
    query.x = c.x;
    query.y = c.y;
    query.z = c.z;
    query.radius = radius;
    query.time = 0;
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(scene_, &query, &context, rise_callback, &q);
    // Spheres (Embree's point query does not call back for them): each assumed to rise, one by
    // one (scenes hold few).
    float r = query.radius;
    for (const float* s : spheres_) r = std::min(r, std::max(0.0f, length(c - Vec3{s[0], s[1], s[2]}) - s[3]));
    return r;
}

}  // namespace sl
