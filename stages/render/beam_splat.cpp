#include "stages/render/beam_splat.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace sl {

void BeamSplat::build(const RenderContext& ctx, const VolumePhotonMap& photons, const SectionBuffer& buffer) {
    const BeamKernel kernel(ctx, buffer, 1);
    const uint32_t n = static_cast<uint32_t>(photons.size());
    const Vec3 eye = ctx.camera.position();
    box_.resize(n);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 4096), [&](const tbb::blocked_range<uint32_t>& r) {
        for (uint32_t i = r.begin(); i != r.end(); ++i) {
            const Vec3 p = photons.position(i);
            // A segment from the camera takes p at most at the radius of p's own distance (the
            // radius grows along the path), kept a little wider against rounding.
            const float dist = length(p - eye), rho = kernel.widest(dist) * 1.001f + 1e-6f;
            Box b{0, -1, 0, -1, 0};
            if (!ctx.camera.pixels_near(p, rho, b.x0, b.x1, b.y0, b.y1)) b = Box{0, -1, 0, -1, 0};
            // A ray passing within rho of p reaches it no nearer than this (its projection).
            b.nearest = (dist - rho) * 0.999f;
            box_[i] = b;
        }
    });
    const int bands = (ctx.height + kBandRows - 1) / kBandRows;
    band_start_.assign(static_cast<size_t>(bands) + 1, 0);
    wide_.clear();
    auto band_span = [&](const Box& b, int& b0, int& b1) {
        b0 = b.y0 / kBandRows;
        b1 = b.y1 / kBandRows;
        return b.y0 <= b.y1 && b1 - b0 < kMaxBands;
    };
    for (uint32_t i = 0; i < n; ++i) {
        int b0, b1;
        if (band_span(box_[i], b0, b1))
            for (int b = b0; b <= b1; ++b) ++band_start_[static_cast<size_t>(b) + 1];
        else if (box_[i].y0 <= box_[i].y1)
            wide_.push_back(i);
    }
    for (int b = 0; b < bands; ++b) band_start_[static_cast<size_t>(b) + 1] += band_start_[static_cast<size_t>(b)];
    band_photons_.resize(band_start_.back());
    std::vector<uint32_t> fill(band_start_.begin(), band_start_.end() - 1);
    for (uint32_t i = 0; i < n; ++i) {
        int b0, b1;
        if (band_span(box_[i], b0, b1))
            for (int b = b0; b <= b1; ++b) band_photons_[fill[static_cast<size_t>(b)]++] = i;
    }
}

void BeamSplat::gather(const RenderContext& ctx, const VolumePhotonMap& photons, int64_t emitted, size_t begin,
                       size_t end, std::span<const CameraSegment> first, SectionBuffer& buffer,
                       BeamCounters& counters) const {
    if (begin >= end) return;
    const BeamKernel kernel(ctx, buffer, emitted);
    const PixelShare& share = buffer.share;
    const size_t width = static_cast<size_t>(ctx.width);
    // What the test reads of each segment, packed (32 bytes); length 0: no segment.
    struct Ray {
        float ox, oy, oz, dx, dy, dz, length, s0;
    };
    std::vector<Ray> rays(end - begin);
    // The farthest end of a segment in each run of the share's tiles (camera distance): a photon
    // beyond it, behind the surfaces those pixels see, is not tested there at all.
    const size_t run0 = begin / PixelShare::kTile;
    std::vector<float> farthest((end - 1) / PixelShare::kTile - run0 + 1, -1.0f);
    const Vec3 eye = ctx.camera.position();
    for (size_t k = 0; k < rays.size(); ++k) {
        const CameraSegment& sg = first[k];
        counters.segments += sg.length > 0;
        rays[k] = {sg.origin.x, sg.origin.y, sg.origin.z, sg.dir.x, sg.dir.y, sg.dir.z,
                   sg.length > 0 ? sg.length : 0.0f, kernel.s0(sg)};
        if (sg.length > 0) {
            float& f = farthest[(begin + k) / PixelShare::kTile - run0];
            f = std::max(f, (length(sg.origin - eye) + sg.length) * 1.001f);
        }
    }
    const float r0 = kernel.r0(), slope = kernel.slope();
    // Photon i against the pixels of row y, columns [x0, x1], that lie in [begin, end): run by
    // run of the share's tiles, so a pixel's place in the buffer costs no division.
    auto photon_in_row = [&](uint32_t i, size_t y, int x0, int x1) {
        const Vec3 p = photons.position(i);
        size_t g = y * width + static_cast<size_t>(x0);
        const size_t g_end = y * width + static_cast<size_t>(x1) + 1;
        while (g < g_end) {
            const size_t run_end = std::min(g_end, (g / PixelShare::kTile + 1) * PixelShare::kTile);
            size_t l;
            if (share.local_of(g, l) && l + (run_end - g) > begin && l < end &&
                farthest[std::max(l, begin) / PixelShare::kTile - run0] >= box_[i].nearest) {
                for (; g < run_end; ++g, ++l) {
                    if (l < begin || l >= end) continue;
                    const Ray& ry = rays[l - begin];
                    if (!(ry.length > 0)) continue;
                    float sp, q;  // the search's own test: the same photons
                    if (VolumePhotonMap::in_cone(p, {ry.ox, ry.oy, ry.oz}, {ry.dx, ry.dy, ry.dz}, ry.length, r0,
                                                 ry.s0, slope, sp, q))
                        kernel.add(first[l - begin], photons.payload(i), sp, q, l, buffer, counters);
                }
            }
            g = run_end;
        }
    };
    const size_t y_first = share.global(begin) / width, y_last = share.global(end - 1) / width;
    for (size_t y = y_first; y <= y_last; ++y) {
        const int yi = static_cast<int>(y);
        const size_t band = y / kBandRows;
        for (size_t k = band_start_[band]; k < band_start_[band + 1]; ++k) {
            const uint32_t i = band_photons_[k];
            const Box& b = box_[i];
            if (yi >= b.y0 && yi <= b.y1) photon_in_row(i, y, b.x0, b.x1);
        }
        for (uint32_t i : wide_) {
            const Box& b = box_[i];
            if (yi >= b.y0 && yi <= b.y1) photon_in_row(i, y, b.x0, b.x1);
        }
    }
}

}  // namespace sl
