#include "stages/render/volume_photon_map.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>

namespace sl {
namespace {

// Nodes of a median-split subtree over n photons: known in advance, so that both halves can
// be built at once into their own, fixed, index ranges.
uint32_t node_count(uint32_t n) {
    if (n <= VolumePhotonMap::kLeaf) return 1;
    return 1 + node_count(n / 2) + node_count(n - n / 2);
}

}  // namespace

uint64_t VolumePhotonMap::bytes() const {
    return all_.capacity() * sizeof(VolumePhoton) + order_.capacity() * 4 + nodes_.capacity() * sizeof(Node) +
           (px_.capacity() + py_.capacity() + pz_.capacity()) * 4 + payload_.capacity() * sizeof(VolumePhotonPayload);
}

void VolumePhotonMap::build(std::span<const std::vector<VolumePhoton>* const> batches) {
    std::vector<size_t> start(batches.size() + 1, 0);
    for (size_t b = 0; b < batches.size(); ++b) start[b + 1] = start[b] + batches[b]->size();
    const size_t n = start.back();
    all_.resize(n);
    tbb::parallel_for(size_t(0), batches.size(), [&](size_t b) {
        std::copy(batches[b]->begin(), batches[b]->end(), all_.begin() + static_cast<ptrdiff_t>(start[b]));
    });
    order_.resize(n);
    for (uint32_t i = 0; i < n; ++i) order_[i] = i;
    nodes_.resize(n > 0 ? node_count(static_cast<uint32_t>(n)) : 0);
    if (n > 0) build_node(0, 0, static_cast<uint32_t>(n));
    px_.resize(n);
    py_.resize(n);
    pz_.resize(n);
    payload_.resize(n);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const VolumePhoton& p = all_[order_[i]];
            px_[i] = p.x; py_[i] = p.y; pz_[i] = p.z;
            payload_[i] = {{p.dx, p.dy, p.dz}, {p.r, p.g, p.b}, p.depth, p.t_ns};
        }
    });
}

void VolumePhotonMap::build_node(uint32_t node, uint32_t begin, uint32_t end) {
    Node& nd = nodes_[node];
    Vec3 lo(INFINITY), hi(-INFINITY);
    for (uint32_t i = begin; i < end; ++i) {
        const VolumePhoton& p = all_[order_[i]];
        lo = vmin(lo, {p.x, p.y, p.z});
        hi = vmax(hi, {p.x, p.y, p.z});
    }
    for (int a = 0; a < 3; ++a) { nd.lo[a] = lo[a]; nd.hi[a] = hi[a]; }
    const uint32_t n = end - begin;
    if (n <= kLeaf) {
        nd.first_or_right = begin;
        nd.count = n;
        return;
    }
    Vec3 ext = hi - lo;
    int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
    const uint32_t mid = begin + n / 2;
    // nth_element is deterministic for a given input; ties are broken by index so that the
    // order does not even depend on the library's pivot choices.
    auto key = [&](uint32_t i) {
        const VolumePhoton& p = all_[i];
        return axis == 0 ? p.x : (axis == 1 ? p.y : p.z);
    };
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](uint32_t a, uint32_t b) {
                         float ka = key(a), kb = key(b);
                         return ka < kb || (ka == kb && a < b);
                     });
    const uint32_t left = node + 1, right = node + 1 + node_count(n / 2);
    nd.first_or_right = right;
    nd.count = 0;
    if (n > 16384) {
        tbb::parallel_invoke([&] { build_node(left, begin, mid); }, [&] { build_node(right, mid, end); });
    } else {
        build_node(left, begin, mid);
        build_node(right, mid, end);
    }
}

}  // namespace sl
