#pragma once
// The emissive triangles of imported meshes (and of a scene file's quads and boxes whose material
// has an emission) as one light: flat arrays, a triangle chosen in
// proportion to its power (area x radiance, times its emission texture's mean), a point on
// it uniformly. Photons leave it cosine-distributed; direct light samples a point on it.
#include <cstdint>
#include <vector>

#include "config/scene_desc.h"

namespace sl {

struct EmitterPoint {
    Vec3 position;
    Vec3 normal;     // unit front normal (counter-clockwise side)
    Vec3 radiance;   // W sr^-1 m^-2 at that point, from the front (and the back if two-sided)
    float pdf_area;  // probability density of the point per m^2 (triangle choice included)
    bool two_sided;
};

class EmissiveTriangles {
public:
    explicit EmissiveTriangles(const SceneDesc& scene);

    bool empty() const { return cdf_.empty(); }
    size_t size() const { return cdf_.size(); }
    Vec3 power() const { return power_; }  // W, both faces of two-sided triangles included

    // What one emissive triangle costs here (its record, its two table entries, and the weight
    // it has while the table is built): the memory plan counts the placed ones with it.
    static uint64_t bytes_per_triangle();

    // A point by power: u1 picks the triangle (and, rescaled, is reused with u2 to place the point).
    EmitterPoint sample(float u1, float u2) const;
    // The density per m^2 with which sample() picks a point on any triangle of material m (a
    // path that met an emitter weighs it against this; sample's choice is by power, so within
    // one material it is the same everywhere). 0 for a material that is not among them.
    float pdf_area_of(const MaterialDesc& m) const;

private:
    Vec3 power_per_area(const MaterialDesc& m) const;
    struct Triangle {
        Vec3 v0, e1, e2, normal;
        Vec3 radiance;   // the material's factor
        float area;
        int texture;     // emission texture or -1
        float uv[6];
        bool two_sided;
    };
    const SceneDesc* scene_;
    std::vector<Triangle> tris_;
    std::vector<float> cdf_;  // cumulative, normalised
    std::vector<float> prob_;
    double total_weight_ = 0;  // the sum of the triangles' choice weights (average power, W)
    Vec3 power_;
};

}  // namespace sl
