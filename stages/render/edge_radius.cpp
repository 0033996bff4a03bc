#include "stages/render/edge_radius.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/oct_normal.h"
#include "stages/render/gather_blockers.h"

namespace sl {
namespace {

// What a pixel's centre ray meets first, in 8 bytes (a 4K image's map is 66 MB while it is
// made): the distance along the ray (negative: nothing) and the normal facing the camera.
struct CentreHit {
    float t = -1;
    OctNormal normal{};
};

constexpr float kSameSurface = GatherRadii::kSameSurface;  // the gather's own
constexpr int kMaxReach = 16;         // pixels searched each way at most
constexpr float kFloor = 1.0f / 64;   // of r0: a guard, not a choice
// Where a cut's mirror stands at least, in radii: the gather's own.
constexpr float kMirrorMin = GatherBlockers::kMirrorMin;
// The edge pixels within this many rings of a pixel (all it searches) have the surface's end
// found between their centre and the pixel's by bisection, to 1/64 of the way: the line can
// stand at the edge itself, not a pixel step short of it (where the shrunk disc would serve half
// the pixel). Within 3 rings only, a far edge pixel's bound (a step round its centre) pulled the
// line back to the pixel's own centre where the edge crosses the pixel: a plate's outermost
// pixels, a quarter of a pixel over its edge, came out 6 % dark (the silhouette test); the
// rays of all rings cost the cathedral no measurable time (docs/design.md).
constexpr int kRefined = kMaxReach;
constexpr int kBisections = 6;
constexpr float kChecks = 200;  // points of a cut's border checked at most (about)
// A pixel whose shrunk disc or cut leaves less than this share of the whole disc tries a star:
// above it a star gains little for its rays (the cathedral's map: the same noise, 40 % less time).
constexpr double kStarBelow = 0.8;
constexpr float kPiF = 3.14159265f;

// An edge pixel q seen from p, on p's tangent plane: what q sees is not p's surface. `mid` is the
// distance of the point half a step short of it (where the radius stops). The surface's end lies
// between w and w - s for s one of sx, sy (offsets from p): for a pixel near p, w is the first
// point found off the surface by bisection and sx the step back to the last one on it (sy zero);
// for the others, w is q's centre and sx, sy a pixel step there along the image's axes (the end
// lies within a step of q's centre along an axis, or it is nearer another edge pixel's).
struct EdgePixel {
    Vec3 w, sx, sy;
    float mid;
    // How much nearer p along u the surface's end may lie than q's centre.
    float slack(Vec3 u) const { return std::max(std::abs(dot(sx, u)), std::abs(dot(sy, u))); }
};

// A candidate cut: a line across `across` (unit, on the tangent plane) at `offset` from p, the
// radius, and the area it leaves (with the mirror at max(offset, radius / 4) on p's other side).
struct Cut {
    double area;
    Vec3 across;
    float offset, radius;
};

// The cuts that leave p a larger disc than the shrunk radius `shrunk` (by 5 % at least), the
// largest first. The lines face the three nearest edge pixels; for each, an edge pixel whose
// surface end lies beyond the line, or beyond its mirror (at max(offset, r0 / 4) on the other
// side of p, as the gather puts it), is accounted for, and the others cap the radius at their
// `mid`. Edge pixels sample the surface's end only along their own directions from p: the
// caller still checks the region a cut keeps.
std::vector<Cut> candidate_cuts(const std::vector<EdgePixel>& found, float r0, float p_step, float shrunk) {
    std::vector<Cut> cuts;
    const double least = 1.05 * 3.141592653589793 * shrunk * shrunk;
    int nearest[3] = {-1, -1, -1};
    for (int i = 0; i < static_cast<int>(found.size()); ++i) {
        for (int j = 0; j < 3; ++j) {
            if (nearest[j] < 0 || found[i].mid < found[nearest[j]].mid) {
                for (int k = 2; k > j; --k) nearest[k] = nearest[k - 1];
                nearest[j] = i;
                break;
            }
        }
    }
    // For a line across u at d (the mirror at max(d, r0 / 4)), edge pixel e is left unaccounted
    // for when its end may lie before the line (lo_e < d) and before the mirror (hi_e > -mirror);
    // with d ascending these sets only grow, so the radius they cap is a running minimum over
    // the edge pixels sorted by the d past which each one counts.
    const float m = kMirrorMin * r0;
    const size_t n = found.size();
    std::vector<float> lo(n), hi(n);
    std::vector<uint32_t> by_d(n), by_lo(n), by_t(n);
    for (int c : nearest) {
        if (c < 0) break;
        const Vec3 u = normalize(found[c].w);
        for (size_t e = 0; e < n; ++e) {
            const float a = dot(found[e].w, u), sl = found[e].slack(u);
            lo[e] = a - sl, hi[e] = a + sl;
        }
        for (size_t e = 0; e < n; ++e) by_d[e] = by_lo[e] = by_t[e] = static_cast<uint32_t>(e);
        // Candidate lines, nearest first: a little behind p's centre at most (the points of the
        // pixel before the line gather with it, the others in the shrunk disc).
        std::sort(by_d.begin(), by_d.end(), [&](uint32_t x, uint32_t y) { return lo[x] < lo[y]; });
        // Up to the mirror's floor (d <= m): e counts once lo_e < d, if hi_e > -m.
        std::sort(by_lo.begin(), by_lo.end(), [&](uint32_t x, uint32_t y) { return lo[x] < lo[y]; });
        // Past it (d > m, the mirror at d): e counts once max(lo_e, -hi_e) < d.
        auto t_of = [&](uint32_t e) { return std::max(lo[e], -hi[e]); };
        std::sort(by_t.begin(), by_t.end(), [&](uint32_t x, uint32_t y) { return t_of(x) < t_of(y); });
        Cut best{least, u, 0, 0};
        size_t i_lo = 0, i_t = 0;
        float r_lo = r0, r_t = r0;
        for (uint32_t cand : by_d) {
            const float d = lo[cand];
            if (!(d >= -0.5f * p_step)) continue;
            if (d >= r0) break;
            float r;
            if (d <= m) {
                for (; i_lo < n && lo[by_lo[i_lo]] < d; ++i_lo)
                    if (hi[by_lo[i_lo]] > -m) r_lo = std::min(r_lo, found[by_lo[i_lo]].mid);
                r = r_lo;
            } else {
                for (; i_t < n && t_of(by_t[i_t]) < d; ++i_t) r_t = std::min(r_t, found[by_t[i_t]].mid);
                r = r_t;
            }
            r = std::max(r, kFloor * r0);
            if (d >= r) continue;  // the line misses the disc: no better than no cut
            const double area = disc_between_lines(r, std::max(d, 0.0f), std::max(d, kMirrorMin * r));
            if (area > best.area) best = Cut{area, u, d, r};
        }
        if (best.radius > 0) cuts.push_back(best);
    }
    std::sort(cuts.begin(), cuts.end(), [](const Cut& x, const Cut& y) { return x.area > y.area; });
    return cuts;
}

// A star's reach in each sector (EdgeStar), from where the surface ends along the rays between
// sectors (`along`, kSectors of them, the first at angle -pi, found ray by ray): no farther than
// the nearer of the sector's two, nor than any edge pixel in the sector (a hole between the
// rays: its end at w - sx when found by bisection, else half a step short of w; the border's
// check comes after), and, as a cut's mirror, no farther than the opposite sector's reach or
// kMirrorMin r0, whichever is more (what is kept stays centred on the point). False when an end
// may reach the point, or lies a step past the horizon.
bool star_reaches(const std::vector<EdgePixel>& found, Vec3 t, Vec3 b, float r0,
                  const float (&along)[EdgeStar::kSectors], float (&reach)[EdgeStar::kSectors]) {
    constexpr int K = EdgeStar::kSectors;
    float end[K];
    for (int k = 0; k < K; ++k) end[k] = std::min({along[k], along[(k + 1) % K], r0});
    for (const EdgePixel& e : found) {
        if (!(e.sx.x < 1e29f)) return false;
        const bool bisected = e.sy.x == 0 && e.sy.y == 0 && e.sy.z == 0;
        const Vec3 w = bisected ? e.w - e.sx : e.w;
        const float nearest = length(w) - (bisected ? 0.0f : 0.5f * std::max(length(e.sx), length(e.sy)));
        if (!(nearest > 0)) return false;
        float& r = end[EdgeStar::sector_of(dot(w, t), dot(w, b))];
        r = std::min(r, nearest);
    }
    for (int k = 0; k < K; ++k) reach[k] = std::min(end[k], std::max(end[(k + K / 2) % K], kMirrorMin * r0));
    return true;
}

}  // namespace

GatherRadii edge_aware_radii(const SceneGeometry& geometry, const PinholeCamera& camera, int width, int height,
                             float r0) {
    const size_t n = static_cast<size_t>(width) * height;
    std::vector<CentreHit> hits(n);
    const Vec3 eye = camera.position();
    tbb::parallel_for(0, height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const Vec3 d = camera.direction(x + 0.5f, y + 0.5f);
            SurfaceHit h;
            CentreHit& c = hits[static_cast<size_t>(y) * width + x];
            if (!geometry.intersect(eye, d, 0, 1e30f, h)) continue;
            c.t = h.t;
            c.normal = encode_normal(dot(h.normal, d) < 0 ? h.normal : -h.normal);
        }
    });
    struct Seen {
        Vec3 position, normal;
    };
    auto decoded = [&](const CentreHit& c, int x, int y) {
        return Seen{eye + camera.direction(x + 0.5f, y + 0.5f) * c.t, decode_normal(c.normal)};
    };
    // Heights off the tangent plane below a tenth of the radius are the same surface (the
    // gather's slack: curved surfaces of curvature radius above ~5 r0).
    const float slack = 0.1f * r0;
    // Whether what q sees ends p's surface: nothing, something behind p's tangent plane, or
    // something turned away on it. In front of the plane is a wall rising (the blockers') or
    // something nearer the eye, behind which p's surface goes on. On the plane, a surface
    // turned toward p is a wall rising from it too (the foot of a wall, a column's base: a
    // concave corner, the blockers'), not the surface's end: a box's top edge turns away.
    auto off = [&](const Seen& p, const Seen& q) {
        const float h = dot(p.normal, q.position - p.position);
        if (h > slack) return false;
        if (h < -slack) return true;
        return dot(p.normal, q.normal) < kSameSurface && !(dot(q.normal, p.position - q.position) > 0);
    };
    auto ends = [&](const Seen& p, const CentreHit& qh, int qx, int qy) {
        return !(qh.t >= 0) || off(p, decoded(qh, qx, qy));
    };
    // The same for the ray through image point (fx, fy), cast now (the bisections, the checks).
    auto ends_at = [&](const Seen& p, float fx, float fy) {
        const Vec3 d = camera.direction(fx, fy);
        SurfaceHit h;
        if (!geometry.intersect(eye, d, 0, 1e30f, h)) return true;
        return off(p, Seen{h.position, dot(h.normal, d) < 0 ? h.normal : -h.normal});
    };
    // Pixels beside an edge, summed over the image (a summed-area table): a pixel with none
    // within its reach keeps r0 without a search (most of them).
    const size_t w1 = static_cast<size_t>(width) + 1;
    std::vector<uint32_t> marked(w1 * (static_cast<size_t>(height) + 1), 0);
    std::vector<uint8_t> mark(n, 0);
    {
        tbb::parallel_for(0, height, [&](int y) {
            for (int x = 0; x < width; ++x) {
                const CentreHit& a = hits[static_cast<size_t>(y) * width + x];
                const Seen pa = a.t >= 0 ? decoded(a, x, y) : Seen{};
                for (int k = 0; k < 2; ++k) {  // the pixel to the right and the one below
                    const int bx = x + (k == 0), by = y + (k == 1);
                    if (bx >= width || by >= height) continue;
                    const CentreHit& b = hits[static_cast<size_t>(by) * width + bx];
                    bool edge;
                    if (!(a.t >= 0) || !(b.t >= 0)) {
                        edge = (a.t >= 0) != (b.t >= 0);
                    } else {
                        edge = ends(pa, b, bx, by) || ends(decoded(b, bx, by), a, x, y);
                    }
                    if (edge) mark[static_cast<size_t>(y) * width + x] = mark[static_cast<size_t>(by) * width + bx] = 1;
                }
            }
        });
        for (int y = 0; y < height; ++y) {
            uint32_t row = 0;
            for (int x = 0; x < width; ++x) {
                row += mark[static_cast<size_t>(y) * width + x];
                marked[(y + 1) * w1 + x + 1] = marked[y * w1 + x + 1] + row;
            }
        }
    }
    auto any_marked = [&](int x0, int y0, int x1, int y1) {  // inclusive corners, clipped
        x0 = std::max(x0, 0), y0 = std::max(y0, 0), x1 = std::min(x1, width - 1), y1 = std::min(y1, height - 1);
        return marked[(y1 + 1) * w1 + x1 + 1] + marked[y0 * w1 + x0] != marked[y0 * w1 + x1 + 1] + marked[(y1 + 1) * w1 + x0];
    };
    GatherRadii out;
    out.radius.assign(n, r0);
    // Each row's cuts (pixel, cut), joined in row order below: only the cuts are held, not a
    // cut's room for every pixel.
    std::vector<std::vector<std::pair<uint32_t, EdgeCut>>> row_cuts(height);
    std::vector<std::vector<std::pair<uint32_t, EdgeStar>>> row_stars(height);
    tbb::parallel_for(0, height, [&](int y) {
        std::vector<EdgePixel> found;
        for (int x = 0; x < width; ++x) {
            const CentreHit& ph = hits[static_cast<size_t>(y) * width + x];
            if (!(ph.t >= 0)) continue;
            const Seen p = decoded(ph, x, y);
            // How far the search must reach: r0 in pixels at this point (the step to the next
            // pixel measured on the tangent plane, whichever way is shorter).
            const float plane = dot(p.normal, p.position - eye);  // < 0: the eye is on the normal's side
            auto on_plane = [&](float px, float py, Vec3& out) {
                const Vec3 d = camera.direction(px, py);
                const float dn = dot(p.normal, d);
                if (!(dn < 0)) return false;
                out = eye + d * (plane / dn);
                return true;
            };
            // Where p's surface ends between p's centre and edge pixel q's, along the image's
            // segment between them, by bisection (rays through points of the image): `lo` the last
            // point found on the surface, `hi` the first off it, as offsets on p's tangent plane.
            auto edge_between = [&](const Seen& p, int x, int y, int qx, int qy, Vec3& lo, Vec3& hi) {
                float a = 0, b = 1;
                for (int i = 0; i < kBisections; ++i) {
                    const float t = 0.5f * (a + b);
                    (ends_at(p, x + 0.5f + t * (qx - x), y + 0.5f + t * (qy - y)) ? b : a) = t;
                }
                Vec3 pa, pb;
                if (!on_plane(x + 0.5f + a * (qx - x), y + 0.5f + a * (qy - y), pa) ||
                    !on_plane(x + 0.5f + b * (qx - x), y + 0.5f + b * (qy - y), pb))
                    return false;
                lo = pa - p.position, hi = pb - p.position;
                return true;
            };
            // Whether all a cut keeps of p's disc is p's surface, as seen through the camera:
            // what ends the surface inside the kept region and not beyond its border is a hole,
            // and a hole as wide as a pixel has an edge pixel there, which the cut's radius
            // accounts for already. So the border is checked: points along the line, the mirror
            // and the rim, a little inside, every half pixel step (about kChecks at most), each
            // through its own ray from the eye.
            auto keeps_only_the_surface = [&](const Seen& p, const Cut& c, float p_step) {
                const float R = c.radius, mirror = std::max(c.offset, kMirrorMin * R);
                const float border = 2 * (c.offset + mirror) + 2 * kPiF * R;  // more than its length
                const float h = std::max(0.5f * p_step, border / kChecks);
                if (!(h > 0) || !(c.offset + mirror > 0) || !(R > 0)) return false;
                const Vec3 v = cross(p.normal, c.across);
                auto on_surface = [&](float sa, float t) {
                    float fx, fy;
                    return camera.project(p.position + c.across * sa + v * t, fx, fy) && !ends_at(p, fx, fy);
                };
                const float inside = 0.25f * h;
                for (const float sa : {c.offset - inside, -mirror + inside}) {  // the two lines
                    const float half = std::sqrt(std::max(0.0f, R * R - sa * sa));
                    const int n = static_cast<int>(std::ceil(std::min(2 * half / h, 2 * kChecks)));
                    for (int j = 0; j <= n; ++j)
                        if (!on_surface(sa, (n > 0 ? 2.0f * j / n - 1 : 0) * half * 0.999f)) return false;
                }
                const float rim = std::max(R - inside, 0.0f);
                const int n = static_cast<int>(std::ceil(std::min(2 * kPiF * rim / h, 2 * kChecks)));
                for (int j = 0; j < n; ++j) {
                    const float a = 2 * kPiF * (j + 0.5f) / n, sa = rim * std::cos(a);
                    if (sa > -mirror && sa < c.offset && !on_surface(sa, rim * std::sin(a))) return false;
                }
                return true;
            };
            // The same for a star: points along each sector's arc and along the steps between
            // sectors' reaches, a little inside, every half pixel step (about 2 kChecks at most).
            auto star_keeps_only_the_surface = [&](const Seen& p, const EdgeStar& st, Vec3 t, Vec3 b, float p_step) {
                constexpr int K = EdgeStar::kSectors;
                constexpr float kSector = 2 * kPiF / K;
                float border = 0;
                for (int k = 0; k < K; ++k)
                    border += st.reach_of(k) * kSector + std::abs(st.reach_of(k) - st.reach_of((k + 1) % K));
                const float h = std::max(0.5f * p_step, border / (2 * kChecks));
                if (!(h > 0)) return false;
                const float inside = 0.25f * h;
                auto on_surface = [&](float rho, float a) {
                    float fx, fy;
                    const Vec3 x = p.position + (t * std::cos(a) + b * std::sin(a)) * rho;
                    return camera.project(x, fx, fy) && !ends_at(p, fx, fy);
                };
                for (int k = 0; k < K; ++k) {
                    const float a0 = k * kSector - kPiF, rk = std::max(st.reach_of(k) - inside, 0.0f);
                    const int n_arc = static_cast<int>(std::ceil(rk * kSector / h));
                    for (int j = 0; j <= n_arc; ++j)
                        if (!on_surface(rk, a0 + kSector * (0.02f + 0.96f * j / std::max(n_arc, 1)))) return false;
                    // The step to the next sector's reach, along their common ray.
                    const float rn = std::max(st.reach_of((k + 1) % K) - inside, 0.0f);
                    const float lo = std::min(rk, rn), hi = std::max(rk, rn);
                    const int n_step = static_cast<int>(std::ceil((hi - lo) / h));
                    for (int j = 1; j < n_step; ++j)
                        if (!on_surface(lo + (hi - lo) * j / n_step, a0 + kSector)) return false;
                }
                return true;
            };
            // How far p's surface goes on from its centre along tangent direction u, up to r0:
            // marched a pixel step at a time over the centre hits of the four pixels round each
            // point (a ray where they leave the image), then, where one of them ends the surface,
            // found with rays of its own: stepped on to the first point off the surface, back to
            // the last one on it, and bisected between the two.
            auto end_along = [&](const Seen& p, Vec3 u, float p_step) {
                const float h = p_step;
                auto off_at = [&](float s) {
                    float fx, fy;
                    return !camera.project(p.position + u * s, fx, fy) || ends_at(p, fx, fy);
                };
                auto near_off = [&](float s) {
                    float fx, fy;
                    if (!camera.project(p.position + u * s, fx, fy)) return true;
                    const int x0 = static_cast<int>(std::floor(fx - 0.5f));
                    const int y0 = static_cast<int>(std::floor(fy - 0.5f));
                    if (x0 < 0 || y0 < 0 || x0 + 1 >= width || y0 + 1 >= height) return ends_at(p, fx, fy);
                    for (int qy = y0; qy <= y0 + 1; ++qy)
                        for (int qx = x0; qx <= x0 + 1; ++qx)
                            if (ends(p, hits[static_cast<size_t>(qy) * width + qx], qx, qy)) return true;
                    return false;
                };
                float on = 0;
                for (float s = h;; s += h) {
                    const float sc = std::min(s, r0);
                    if (near_off(sc)) {
                        float a = on, c = sc;
                        while (!off_at(c)) {
                            if (c >= r0) return r0;
                            a = c;
                            c = std::min(c + h, r0);
                        }
                        while (a > 0 && off_at(a)) {
                            c = a;
                            a = std::max(a - h, 0.0f);
                        }
                        for (int i = 0; i < kBisections; ++i) {
                            const float m = 0.5f * (a + c);
                            (off_at(m) ? c : a) = m;
                        }
                        return a;
                    }
                    on = sc;
                    if (sc >= r0) return r0;
                }
            };
            Vec3 ax, ay;
            float step = 1e30f;
            if (on_plane(x + 1.5f, y + 0.5f, ax)) step = std::min(step, length(ax - p.position));
            if (on_plane(x + 0.5f, y + 1.5f, ay)) step = std::min(step, length(ay - p.position));
            if (!(step > 0) || step >= 1e30f) continue;
            const int reach = std::min(kMaxReach, static_cast<int>(std::ceil(r0 / step)) + 1);
            if (!any_marked(x - reach, y - reach, x + reach, y + reach)) continue;
            // The first ring with a marked pixel: what ends p's surface is marked (with the pixel
            // before it, which the same test finds on p's surface).
            int first = 1;
            while (!any_marked(x - first, y - first, x + first, y + first)) ++first;
            // (A silhouette's pixel that sees the floor behind at its centre keeps the floor's
            // radius for its points on the object too: halving it as well cut that pixel's bias
            // little and cost 14 % more per-pixel noise in a Cornell box's pulse.)
            // Every pixel within reach that ends p's surface, ring by ring outward (each side of
            // a ring only when the summed-area table has a marked pixel on it).
            found.clear();
            auto visit = [&](int qx, int qy, int k) {
                if (!mark[static_cast<size_t>(qy) * width + qx]) return;
                if (!ends(p, hits[static_cast<size_t>(qy) * width + qx], qx, qy)) return;
                Vec3 xq;
                if (!on_plane(qx + 0.5f, qy + 0.5f, xq)) return;
                const int dx = qx - x, dy = qy - y;
                const float kq = std::sqrt(static_cast<float>(dx * dx + dy * dy));
                const Vec3 w = xq - p.position;
                // The edge lies between q and the last pixel before it: half a pixel short of q
                // for the radius; for a cut's line, found by bisection or within a step of q.
                const float mid = (kq - 0.5f) / kq * length(w);
                if (!(mid < r0)) return;
                Vec3 lo, hi;
                if (k <= kRefined && edge_between(p, x, y, qx, qy, lo, hi)) {
                    found.push_back({hi, hi - lo, Vec3(0), mid});
                    return;
                }
                Vec3 qx1, qy1;
                if (!on_plane(qx + 1.5f, qy + 0.5f, qx1) || !on_plane(qx + 0.5f, qy + 1.5f, qy1)) {
                    found.push_back({w, Vec3(1e30f), Vec3(1e30f), mid});  // a step past the horizon: no line accounts for q
                    return;
                }
                found.push_back({w, qx1 - xq, qy1 - xq, mid});
            };
            for (int k = first; k <= reach; ++k) {
                const int x0 = std::max(x - k, 0), x1 = std::min(x + k, width - 1);
                for (const int qy : {y - k, y + k}) {  // the top and bottom rows
                    if (qy < 0 || qy >= height || !any_marked(x0, qy, x1, qy)) continue;
                    for (int qx = x0; qx <= x1; ++qx) visit(qx, qy, k);
                }
                const int y0 = std::max(y - k + 1, 0), y1 = std::min(y + k - 1, height - 1);
                for (const int qx : {x - k, x + k}) {  // the left and right columns between them
                    if (qx < 0 || qx >= width || y0 > y1 || !any_marked(qx, y0, qx, y1)) continue;
                    for (int qy = y0; qy <= y1; ++qy) visit(qx, qy, k);
                }
            }
            if (found.empty()) continue;
            float best = r0;
            for (const EdgePixel& e : found) best = std::min(best, e.mid);
            best = std::max(best, kFloor * r0);
            out.radius[static_cast<size_t>(y) * width + x] = best;
            Vec3 across;
            float offset = 0, radius = 0;
            bool cut = false;
            double cut_area = 0;
            for (const Cut& c : candidate_cuts(found, r0, step, best)) {
                if (!keeps_only_the_surface(p, c, step)) continue;
                across = c.across, offset = c.offset, radius = c.radius, cut = true, cut_area = c.area;
                break;
            }
            // Where no line accounts for the edge pixels, or its cut leaves little: a star, if it
            // leaves more than the shrunk disc (by 5 % at least) and than the cut, and its border
            // is all on the surface.
            const double have = cut ? cut_area : kPiF * best * best;
            if (have < kStarBelow * kPiF * r0 * r0) {
                Vec3 t, b;
                make_basis(p.normal, t, b);
                float along[EdgeStar::kSectors], reach[EdgeStar::kSectors];
                for (int j = 0; j < EdgeStar::kSectors; ++j) {
                    const float a = j * (2 * kPiF / EdgeStar::kSectors) - kPiF;
                    along[j] = end_along(p, t * std::cos(a) + b * std::sin(a), step);
                }
                EdgeStar st;
                st.centre = p.position;
                st.normal = encode_normal(p.normal);
                st.scale = r0 / 255;
                st.shrunk = best / r0;
                if (star_reaches(found, t, b, r0, along, reach)) {
                    for (int k = 0; k < EdgeStar::kSectors; ++k)
                        st.reach[k] = static_cast<uint8_t>(std::clamp(std::floor(reach[k] / st.scale), 0.0f, 255.0f));
                    const double area = st.area(r0);
                    if (area > 1.05 * kPiF * best * best && (!cut || area > cut_area) &&
                        star_keeps_only_the_surface(p, st, t, b, step)) {
                        const size_t i = static_cast<size_t>(y) * width + x;
                        out.radius[i] = r0;
                        row_stars[y].push_back({static_cast<uint32_t>(i), st});
                        continue;
                    }
                }
            }
            if (!cut) continue;
            const size_t i = static_cast<size_t>(y) * width + x;
            out.radius[i] = radius;
            row_cuts[y].push_back({static_cast<uint32_t>(i),
                                   EdgeCut{encode_normal(across), dot(across, p.position) + offset,
                                           encode_normal(p.normal), dot(p.normal, p.position), best / radius}});
        }
    });
    // Joined in row order, an index a pixel only when there is any.
    auto join = [n](const auto& rows, auto& index, auto& items) {
        size_t count = 0;
        for (const auto& row : rows) count += row.size();
        if (count == 0) return;
        index.assign(n, 0);
        items.reserve(count);
        for (const auto& row : rows) {
            for (const auto& [i, c] : row) {
                items.push_back(c);
                index[i] = static_cast<uint32_t>(items.size());
            }
        }
    };
    join(row_cuts, out.cut_of, out.cuts);
    join(row_stars, out.star_of, out.stars);
    if (!out.cuts.empty() || !out.stars.empty()) {
        out.plane.resize(n);
        tbb::parallel_for(0, height, [&](int y) {
            for (int x = 0; x < width; ++x) {
                const size_t i = static_cast<size_t>(y) * width + x;
                if (!(hits[i].t >= 0)) continue;
                const Seen s = decoded(hits[i], x, y);
                out.plane[i] = {hits[i].normal, dot(s.normal, s.position)};
            }
        });
    }
    return out;
}

double disc_between_lines(double R, double near, double far) {
    auto segment = [R](double h) {  // the disc beyond a chord h >= 0 from the centre
        if (h >= R) return 0.0;
        return R * R * std::acos(h / R) - h * std::sqrt(R * R - h * h);
    };
    return 3.141592653589793 * R * R - segment(std::max(near, 0.0)) - segment(std::max(far, 0.0));
}

}  // namespace sl
