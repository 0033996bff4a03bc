#include "stages/render/gather.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>

#include "core/sampling.h"

namespace sl {

void gather_photons(const RenderContext& ctx, const VisiblePoints& vps, const PhotonMap& photons,
                    int64_t photons_per_pass, SectionBuffer& buffer) {
    const float alpha = ctx.scene.render.alpha;
    const Timeline& tl = ctx.timeline;
    const SectionLayout& layout = buffer.layout;
    const double inv_count = 1.0 / static_cast<double>(std::max<int64_t>(photons_per_pass, 1));
    // Normals closer than ~45 degrees count as the same surface: keeps corners from leaking.
    constexpr float kSameSurface = 0.7f;

    double max_r2 = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, ctx.pixels(), 512), 0.0,
        [&](const tbb::blocked_range<size_t>& r, double local_max) {
            for (size_t p = r.begin(); p != r.end(); ++p) {
                double& r2 = buffer.radius2[p];
                if (vps.valid[p]) {
                    const float px = vps.px[p], py = vps.py[p], pz = vps.pz[p];
                    const Vec3 n = decode_normal(vps.normal[p]);
                    const float nx = n.x, ny = n.y, nz = n.z;
                    const uint32_t depth_left = vps.depth_left[p];
                    const double back_ns = vps.camera_ns.empty() ? 0.0 : vps.camera_ns[p];
                    // This pass's estimate: f * flux / (pi R^2 * photons emitted this pass).
                    const float k = static_cast<float>(inv_count / (kPi * r2));
                    const float wr = vps.wr[p] * k, wg = vps.wg[p] * k, wb = vps.wb[p] * k;
                    uint32_t found = 0;
                    photons.for_each_near(px, py, pz, static_cast<float>(r2), [&](const PhotonRecord& ph) {
                        // cos(angle) < kSameSurface, without normalising the decoded normal.
                        const Vec3 pn = decode_normal_unnormalized(ph.normal);
                        const float c = pn.x * nx + pn.y * ny + pn.z * nz;
                        if (c <= 0 || c * c < kSameSurface * kSameSurface * dot(pn, pn)) return;
                        if (ph.depth > depth_left) return;
                        ++found;
                        int s = layout.slot_of_bucket(tl.bucket(ph.t_ns + back_ns));
                        float* acc = buffer.slot(p, s);
                        acc[0] += wr * ph.r;
                        acc[1] += wg * ph.g;
                        acc[2] += wb * ph.b;
                    });
                    if (found > 0) {
                        double n = buffer.photon_count[p];
                        double n_new = n + alpha * found;
                        r2 *= n_new / (n + found);
                        buffer.photon_count[p] = n_new;
                    }
                }
                local_max = std::max(local_max, r2);
            }
            return local_max;
        },
        [](double a, double b) { return std::max(a, b); });
    buffer.max_radius = std::sqrt(max_r2);
    ++buffer.passes_done;
}

}  // namespace sl
