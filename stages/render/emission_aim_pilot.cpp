#include "stages/render/emission_aim_pilot.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/oct_normal.h"
#include "core/rng.h"
#include "core/specular_path.h"
#include "stages/render/photon_map.h"
#include "stages/render/render_context.h"

namespace sl {
namespace {

constexpr uint64_t kSeed = 0x5a1dull;
constexpr int kRaysAcross = 128;     // camera rays a row of the grid, at most
constexpr int kCellsAcross = 64;     // seen cells along the scene's diagonal
constexpr int kCameraVertices = 6;   // a camera path's vertices through mirrors and glass
constexpr uint8_t kVolumeBit = 1u << 6;

// The cells of space the camera sees, one byte each: bit k (k < 6) for a surface whose side
// faces along +x, -x, +y, -y, +z, -z (0, 1, ... 5), bit 6 for the medium.
class SeenCells {
public:
    SeenCells(Vec3 lo, Vec3 hi) {
        const Vec3 e = hi - lo;
        const float diag = length(e);
        cell_ = diag > 0 ? diag / kCellsAcross : 1.0f;
        lo_ = lo - Vec3(cell_);
        for (int a = 0; a < 3; ++a) n_[a] = std::clamp(static_cast<int>(std::ceil(e[a] / cell_)) + 2, 1, 4 * kCellsAcross);
        bits_.assign(static_cast<size_t>(n_[0]) * n_[1] * n_[2], 0);
    }
    float cell() const { return cell_; }

    // The sides a normal shows: every axis it leans along by more than 0.3 (an octagonal
    // column's face leans along two), so that a photon's record on it finds one of them.
    static uint8_t sides_of(Vec3 n) {
        uint8_t b = 0;
        for (int a = 0; a < 3; ++a)
            if (std::abs(n[a]) > 0.3f) b |= static_cast<uint8_t>(1u << (2 * a + (n[a] < 0)));
        return b;
    }
    // The one side a record is matched by: its normal's largest component.
    static uint8_t side_of(Vec3 n) {
        int a = 0;
        for (int k = 1; k < 3; ++k)
            if (std::abs(n[k]) > std::abs(n[a])) a = k;
        return static_cast<uint8_t>(1u << (2 * a + (n[a] < 0)));
    }

    void mark(Vec3 p, uint8_t bits) {
        if (const int64_t c = index(p); c >= 0) bits_[static_cast<size_t>(c)] |= bits;
    }
    bool seen(Vec3 p, uint8_t bit) const {
        const int64_t c = index(p);
        return c >= 0 && (bits_[static_cast<size_t>(c)] & bit);
    }
    // Every cell takes its neighbours' bits: the grid of rays leaves gaps a cell wide.
    void grow() {
        const int64_t stride[3] = {1, n_[0], static_cast<int64_t>(n_[0]) * n_[1]};
        for (int a = 0; a < 3; ++a) {
            std::vector<uint8_t> out(bits_);
            for (int z = 0; z < n_[2]; ++z)
                for (int y = 0; y < n_[1]; ++y)
                    for (int x = 0; x < n_[0]; ++x) {
                        const int at[3] = {x, y, z};
                        const int64_t c = x + stride[1] * y + stride[2] * z;
                        if (at[a] > 0) out[static_cast<size_t>(c)] |= bits_[static_cast<size_t>(c - stride[a])];
                        if (at[a] + 1 < n_[a]) out[static_cast<size_t>(c)] |= bits_[static_cast<size_t>(c + stride[a])];
                    }
            bits_.swap(out);
        }
    }

private:
    int64_t index(Vec3 p) const {
        int64_t c = 0, stride = 1;
        for (int a = 0; a < 3; ++a) {
            const float f = (p[a] - lo_[a]) / cell_;
            if (!(f >= 0 && f < static_cast<float>(n_[a]))) return -1;
            c += stride * static_cast<int64_t>(f);
            stride *= n_[a];
        }
        return c;
    }
    Vec3 lo_;
    float cell_ = 1;
    int n_[3] = {1, 1, 1};
    std::vector<uint8_t> bits_;
};

// Step 1: rays through a grid of pixel centres, followed through mirrors and glass.
SeenCells seen_by_camera(const RenderContext& ctx) {
    Vec3 lo = ctx.geometry.bounds_min(), hi = ctx.geometry.bounds_max();
    if (ctx.medium) {
        lo = vmin(lo, ctx.medium->box_min());
        hi = vmax(hi, ctx.medium->box_max());
    }
    SeenCells seen(lo, hi);
    const int step = std::max(1, (std::max(ctx.width, ctx.height) + kRaysAcross - 1) / kRaysAcross);
    Rng rng(kSeed, 1);
    for (int py = step / 2; py < ctx.height; py += step)
        for (int px = step / 2; px < ctx.width; px += step) {
            Vec3 o = ctx.camera.position();
            Vec3 d = ctx.camera.direction(static_cast<float>(px) + 0.5f, static_cast<float>(py) + 0.5f);
            bool inside = false;
            float inside_ior = 1;
            for (int v = 0; v < kCameraVertices; ++v) {
                SurfaceHit hit;
                const bool found = ctx.geometry.intersect(o, d, 1e-7f, 1e30f, hit);
                float t0, t1;
                if (ctx.medium && !inside && ctx.medium->clip(o, d, 0, found ? hit.t : 1e30f, t0, t1)) {
                    // Counted steps, not s += step: far from the origin a float step may add nothing.
                    const double step = 0.5 * seen.cell(), span = static_cast<double>(t1) - t0;
                    const int64_t steps = span > 0 ? std::min<int64_t>(static_cast<int64_t>(span / step), 4 * kCellsAcross) : 0;
                    for (int64_t k = 0; k <= steps; ++k) seen.mark(o + d * static_cast<float>(t0 + k * step), kVolumeBit);
                }
                if (!found || hit.light >= 0) break;
                const SurfaceMaterial& m = ctx.materials[hit.material];
                if (m.type == MaterialType::Diffuse || m.glossy != GlossyUse::None) {
                    const Vec3 ns = dot(d, hit.normal) < 0 ? hit.shading_normal : -hit.shading_normal;
                    seen.mark(hit.position, SeenCells::sides_of(ns));
                    break;
                }
                follow_specular(m, hit, o, d, inside, inside_ior, rng);
            }
        }
    seen.grow();
    return seen;
}

std::vector<double> usefulness(const RenderContext& ctx, size_t light, const SeenCells& seen) {
    const int n = kAimCells;
    std::vector<double> out(static_cast<size_t>(n) * n, 0.0);
    tbb::parallel_for(0, n * n, [&](int c) {
        const int i = c % n, j = c / n;
        Rng rng(kSeed, 2, light, static_cast<uint64_t>(c));
        std::vector<PhotonRecord> records;
        std::vector<VolumePhoton> volume;
        double sum = 0;
        for (int k = 0; k < kAimPathsPerCell; ++k) {
            const float a1 = (static_cast<float>(i) + rng.uniform()) / n, a2 = (static_cast<float>(j) + rng.uniform()) / n;
            const EmittedPhoton e = ctx.lights.emit_from(light, a1, a2, rng);
            const double start = average(e.flux);
            if (!(start > 0)) continue;
            records.clear();
            volume.clear();
            trace_photon_path(ctx, e, rng, records, &volume);
            for (const PhotonRecord& r : records)
                if (seen.seen(Vec3(r.x, r.y, r.z), SeenCells::side_of(decode_normal(r.normal))))
                    sum += average(Vec3(r.r, r.g, r.b)) / start;
            for (const VolumePhoton& v : volume)
                if (seen.seen(Vec3(v.x, v.y, v.z), kVolumeBit)) sum += average(Vec3(v.r, v.g, v.b)) / start;
        }
        out[static_cast<size_t>(c)] = sum / kAimPathsPerCell;
    });
    return out;
}

}  // namespace

std::vector<double> light_usefulness(const RenderContext& ctx, size_t light) {
    return usefulness(ctx, light, seen_by_camera(ctx));
}

double aim_gain(const std::vector<double>& u, double floor) {
    // The share of draws in a cell, weighed by how useful the cell is: aimed (the table's
    // probabilities) over uniform (1 / cells each).
    double total = 0;
    for (double v : u) total += v > 0 ? v : 0;
    if (!(total > 0) || u.empty()) return 1;
    const double cells = static_cast<double>(u.size());
    double aimed = 0;
    for (double v : u) {
        const double w = v > 0 ? v : 0;
        aimed += ((1 - floor) * w / total + floor / cells) * w;
    }
    return aimed / (total / cells);
}

void aim_lights(RenderContext& ctx) {
    if (ctx.width <= 0 || ctx.height <= 0) return;
    std::vector<size_t> lights;
    for (size_t i = 0; i < ctx.lights.count(); ++i)
        if (ctx.lights.aimable(i) && ctx.lights.power_of(i) > 0) lights.push_back(i);
    if (lights.empty()) return;
    // The most powerful first (ties by index: every process picks the same).
    std::stable_sort(lights.begin(), lights.end(),
                     [&](size_t a, size_t b) { return ctx.lights.power_of(a) > ctx.lights.power_of(b); });
    if (lights.size() > kAimMostLights) lights.resize(kAimMostLights);
    const SeenCells seen = seen_by_camera(ctx);
    for (size_t i : lights) {
        const std::vector<double> u = usefulness(ctx, i, seen);
        if (aim_gain(u, kAimFloor) >= kAimMinGain) ctx.lights.aim(i, EmissionAim(kAimCells, u, kAimFloor));
    }
}

}  // namespace sl
