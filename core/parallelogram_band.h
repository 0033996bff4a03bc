#pragma once
// The points of a parallelogram (a quad light) seen from a point x, sorted by their distance to
// x: the distances it spans, and a point drawn from the part of it whose distance lies in a band
// [d0, d1). With a pulse, the light of each part reaches x in its own frame; drawing one point per
// frame's band gives every frame its own sample (stages/render/direct_by_frames.h) instead of one
// sample landing in one of them.
//
// In the parallelogram's plane the band is an annulus round x's foot point. A point is drawn
// with its squared radius uniform over the band and its angle uniform over the arcs of that
// circle inside the parallelogram; `weight` is the inverse of that point's density by area:
// E[f(y) weight] is the integral of f over the band's part of the parallelogram.
#include "foundation/vec3.h"

namespace sl {

class ParallelogramFromPoint {
public:
    // corner and two edges; x the point it is seen from.
    ParallelogramFromPoint(Vec3 x, Vec3 corner, Vec3 edge1, Vec3 edge2);

    bool valid() const { return valid_; }  // a parallelogram with some area
    double min_distance() const { return d_min_; }
    double max_distance() const { return d_max_; }

    // A point y of the parallelogram with |y - x| in [d0, d1) (u1: the radius, u2: the angle)
    // and its weight; false when the draw lands on a circle that misses the parallelogram
    // (weight 0: the band's estimate is still unbiased) or the band holds none of it.
    bool sample_band(double d0, double d1, float u1, float u2, Vec3& y, double& weight) const;

private:
    // The arcs of the circle of radius rho round the foot point inside the parallelogram, as
    // angle intervals in [0, 2 pi); returns how many (at most kMaxArcs).
    static constexpr int kMaxArcs = 8;
    int arcs(double rho, double lo[kMaxArcs], double hi[kMaxArcs]) const;

    bool valid_ = false;
    Vec3 corner_, t1_, t2_;   // the plane's frame: corner and two unit axes in it
    double px_ = 0, py_ = 0;  // x's foot point in that frame
    double z2_ = 0;           // x's squared height over the plane
    double vx_[4]{}, vy_[4]{};   // the corners, counter-clockwise
    double mx_[4]{}, my_[4]{};   // each edge's inward unit normal
    double inside_[4]{};         // the foot point's distance inside each edge's line
    double theta_[4]{};          // each inward normal's angle, atan2(my, mx): once, not per band
    double rho_min2_ = 0, rho_max2_ = 0;
    double d_min_ = 0, d_max_ = 0;
};

}  // namespace sl
