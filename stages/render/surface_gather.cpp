#include "stages/render/surface_gather.h"

#include <algorithm>

#include "core/sampling.h"

namespace sl {

uint32_t gather_surface_at(const RenderContext& ctx, const VisiblePoint& vp, const PhotonMap& photons,
                           int64_t photons_emitted, size_t pixel, SectionBuffer& buffer,
                           DepositQueue& deposits) {
    const BucketFinder bucket(ctx.timeline);  // every photon found asks it
    const SectionLayout& layout = buffer.layout;
    // Normals closer than ~45 degrees count as the same surface: keeps corners from leaking.
    constexpr float kSameSurface = 0.7f;
    const double inv_count = 1.0 / static_cast<double>(std::max<int64_t>(photons_emitted, 1));
    double& r2 = buffer.radius2[pixel];
    // This pass's estimate: f * flux / (pi R^2 * photons emitted this pass).
    const float k = static_cast<float>(inv_count / (kPi * r2));
    const float wr = vp.weight.x * k, wg = vp.weight.y * k, wb = vp.weight.z * k;
    const Vec3 n = vp.normal;
    uint32_t found = 0;
    photons.for_each_near(vp.position.x, vp.position.y, vp.position.z, static_cast<float>(r2),
                          [&](const PhotonRecord& ph) {
        // cos(angle) < kSameSurface, without normalising the decoded normal.
        const Vec3 pn = decode_normal_unnormalized(ph.normal);
        const float c = dot(pn, n);
        if (c <= 0 || c * c < kSameSurface * kSameSurface * dot(pn, pn)) return;
        if (ph.depth > vp.depth_left) return;
        ++found;
        const int s = layout.slot_of_bucket(bucket(ph.t_ns + vp.camera_ns));
        if (s < 0) return;
        deposits.add(buffer.slot(pixel, s), wr * ph.r, wg * ph.g, wb * ph.b);
    });
    if (found > 0) {
        const float alpha = ctx.render.alpha;
        const double count = buffer.photon_count[pixel];
        const double count_new = count + alpha * found;
        r2 *= count_new / (count + found);
        buffer.photon_count[pixel] = count_new;
    }
    return found;
}

}  // namespace sl
