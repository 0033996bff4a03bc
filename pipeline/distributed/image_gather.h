#pragma once
// Whole images on rank 0 from the pixels each rank owns (PixelShare: tiles dealt round-robin).
#include <vector>

#include "stages/render/rank_exchange.h"

namespace sl {

// `rgb`: this rank's own pixels (3 floats each, in local order). Afterwards rank 0's `rgb` is the
// whole image of `pixels` pixels in image order; the other ranks' is empty. The channel: Frames
// on the way to the outputs, Passes from within a section's passes (--preview).
void gather_image(RankExchange& ex, size_t pixels, std::vector<float>& rgb, Channel channel = Channel::Frames);

// The inverse: rank 0's whole image `whole` (image order; read on rank 0 only) cut into the
// ranks' shares; each rank's own pixels (local order) in `mine`.
void scatter_image(RankExchange& ex, size_t pixels, const std::vector<float>& whole, std::vector<float>& mine,
                   Channel channel);

// Every rank's values, concatenated in rank order, on rank 0 (empty elsewhere).
void gather_values(RankExchange& ex, std::vector<float>& values);

}  // namespace sl
