#pragma once
// One pass's volume photons (scattering events in the medium) in a BVH built for the beam
// radiance estimate: a camera segment finds every photon whose distance to it is below r
// without marching. Median-split BVH over the photon positions, rebuilt each pass; node
// boxes are tight and grown by r at query time (r changes every pass). Positions are kept
// apart (SoA, leaf order) from what is read only on a hit.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "foundation/vec3.h"

namespace sl {
struct VolumePhoton {
    float x, y, z;
    float dx, dy, dz;  // direction of travel when it scattered (before the new direction)
    float r, g, b;     // flux of the emitted path after the event's weight (W)
    uint32_t depth;    // scattering vertices from the light, this one included
    double t_ns;       // arrival time at this point
};

struct VolumePhotonPayload {
    Vec3 dir, flux;
    uint32_t depth;
    double t_ns;
};

class VolumePhotonMap {
public:
    // Concatenates the batches (in order) and builds the tree; the same input gives the same
    // tree and leaf order for any thread count.
    void build(std::span<const std::vector<VolumePhoton>* const> batches);

    size_t size() const { return px_.size(); }
    uint64_t bytes() const;
    // Bytes of one pass's volume photons (`events` of them): each in its batch and concatenated,
    // its index, its position (SoA) and payload in leaf order, and the tree's nodes (about two
    // per kLeaf photons), computed before anything is allocated (pipeline/memory_plan.cpp).
    static uint64_t bytes_needed(uint64_t events) {
        return events * (2 * sizeof(VolumePhoton) + sizeof(uint32_t) + 3 * sizeof(float) +
                         sizeof(VolumePhotonPayload)) +
               (2 * events / kLeaf + 1) * sizeof(Node);
    }
    const VolumePhotonPayload& payload(uint32_t i) const { return payload_[i]; }
    Vec3 position(uint32_t i) const { return {px_[i], py_[i], pz_[i]}; }  // i in leaf order

    // Calls f(photon index, s) for every photon whose projection s onto o + s d lies in
    // [0, length] and whose distance to that line is below sqrt(r2). d is unit length.
    template <class F>
    void for_each_along(Vec3 o, Vec3 d, float length, float r2, F&& f) const;

    // The same for a radius that grows along the line: photon i is taken when its distance
    // to the line is below r(s) = max(r0, s0 + slope s) (s0 may be negative), and f(i, s, r(s)^2) is
    // called. The tree is searched with the radius at the segment's far end.
    template <class F>
    void for_each_along_cone(Vec3 o, Vec3 d, float length, float r0, float s0, float slope, F&& f) const;

    static constexpr uint32_t kLeaf = 8;  // <= 32: a leaf's hits fit a bit mask

    // The cone's test, written once for the search above and the photons' side (beam_splat.cpp):
    // whether the photon at p lies within r(s) = max(r0, s0 + slope s) of o + s d, s in
    // [0, length]; s and r(s)^2 are returned. The offset is computed from the offset vector, not
    // |v|^2 - s^2, so it does not cancel far from o.
    static bool in_cone(Vec3 p, Vec3 o, Vec3 d, float length, float r0, float s0, float slope, float& s,
                        float& q) {
        const float vx = p.x - o.x, vy = p.y - o.y, vz = p.z - o.z;
        s = vx * d.x + vy * d.y + vz * d.z;
        const float qx = vx - d.x * s, qy = vy - d.y * s, qz = vz - d.z * s;
        const float rs = std::max(r0, s0 + slope * s);
        q = rs * rs;
        return (s >= 0) & (s <= length) & (qx * qx + qy * qy + qz * qz < q);
    }

private:
    struct Node {
        float lo[3], hi[3];
        uint32_t first_or_right;  // leaf: first photon; interior: right child (left is next)
        uint32_t count;           // leaf: photons (> 0); interior: 0
    };
    void build_node(uint32_t node, uint32_t begin, uint32_t end);
    template <class Leaf>
    void for_each_leaf_near(Vec3 o, Vec3 d, float length, float r, Leaf&& leaf) const;

    std::vector<VolumePhoton> all_;   // concatenated batches
    std::vector<uint32_t> order_;     // photon index in leaf order
    std::vector<Node> nodes_;
    std::vector<float> px_, py_, pz_;  // leaf order
    std::vector<VolumePhotonPayload> payload_;
};

// The leaves whose boxes, grown by r, the segment o + t d (0 <= t <= length) passes through:
// leaf(first, count) for each. Shared by the cylinder and the cone below.
template <class Leaf>
void VolumePhotonMap::for_each_leaf_near(Vec3 o, Vec3 d, float length, float r, Leaf&& leaf) const {
    // A zero component becomes tiny: slab distances stay finite, never 0 * inf = NaN.
    auto inv = [](float v) { return 1.0f / (v == 0 ? 1e-30f : v); };
    const float ix = inv(d.x), iy = inv(d.y), iz = inv(d.z);
    uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& n = nodes_[stack[--top]];
        float t0 = 0, t1 = length;
        {
            float a = (n.lo[0] - r - o.x) * ix, b = (n.hi[0] + r - o.x) * ix;
            t0 = std::max(t0, std::min(a, b)); t1 = std::min(t1, std::max(a, b));
            a = (n.lo[1] - r - o.y) * iy; b = (n.hi[1] + r - o.y) * iy;
            t0 = std::max(t0, std::min(a, b)); t1 = std::min(t1, std::max(a, b));
            a = (n.lo[2] - r - o.z) * iz; b = (n.hi[2] + r - o.z) * iz;
            t0 = std::max(t0, std::min(a, b)); t1 = std::min(t1, std::max(a, b));
        }
        if (t0 > t1) continue;
        if (n.count == 0) {
            stack[top++] = n.first_or_right;
            stack[top++] = static_cast<uint32_t>(&n - nodes_.data()) + 1;
            continue;
        }
        leaf(n.first_or_right, n.count);
    }
}

template <class F>
void VolumePhotonMap::for_each_along(Vec3 o, Vec3 d, float length, float r2, F&& f) const {
    if (nodes_.empty() || !(length > 0)) return;
    for_each_leaf_near(o, d, length, std::sqrt(r2), [&](uint32_t first, uint32_t count) {
        // Branch-free over the leaf, then the few hits.
        uint32_t mask = 0;
        for (uint32_t k = 0; k < count; ++k) {
            const float vx = px_[first + k] - o.x, vy = py_[first + k] - o.y, vz = pz_[first + k] - o.z;
            const float s = vx * d.x + vy * d.y + vz * d.z;
            // The perpendicular offset itself, not |v|^2 - s^2: no cancellation far away.
            const float qx = vx - d.x * s, qy = vy - d.y * s, qz = vz - d.z * s;
            const bool in = (s >= 0) & (s <= length) & (qx * qx + qy * qy + qz * qz < r2);
            mask |= static_cast<uint32_t>(in) << k;
        }
        while (mask) {
            const uint32_t i = first + static_cast<uint32_t>(std::countr_zero(mask));
            mask &= mask - 1;
            f(i, (px_[i] - o.x) * d.x + (py_[i] - o.y) * d.y + (pz_[i] - o.z) * d.z);
        }
    });
}

template <class F>
void VolumePhotonMap::for_each_along_cone(Vec3 o, Vec3 d, float length, float r0, float s0, float slope, F&& f) const {
    if (nodes_.empty() || !(length > 0)) return;
    const float r = std::max(r0, s0 + slope * length);  // the widest, at the far end
    for_each_leaf_near(o, d, length, r, [&](uint32_t first, uint32_t count) {
        uint32_t mask = 0;
        float ss[kLeaf], rr[kLeaf];
        for (uint32_t k = 0; k < count; ++k) {
            const Vec3 p{px_[first + k], py_[first + k], pz_[first + k]};
            mask |= static_cast<uint32_t>(in_cone(p, o, d, length, r0, s0, slope, ss[k], rr[k])) << k;
        }
        while (mask) {
            const uint32_t k = static_cast<uint32_t>(std::countr_zero(mask));
            mask &= mask - 1;
            f(first + k, ss[k], rr[k]);
        }
    });
}

}  // namespace sl
