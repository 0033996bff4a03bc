#include "pipeline/distributed/image_gather.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace sl {

void gather_image(RankExchange& ex, size_t pixels, std::vector<float>& rgb, Channel channel) {
    std::vector<char>& all = ex.image_buffer[static_cast<int>(channel)];  // kept between frames
    std::vector<uint64_t> counts;
    ex.gather(channel, rgb.data(), rgb.size() * sizeof(float), all, counts);
    if (ex.rank() != 0) {
        rgb.clear();
        return;
    }
    rgb.assign(pixels * 3, 0.0f);
    const char* at = all.data();
    constexpr size_t kTile = PixelShare::kTile;
    for (int r = 0; r < ex.ranks(); ++r) {
        const PixelShare share{r, ex.ranks(), pixels};
        if (counts[static_cast<size_t>(r)] != share.count() * 3 * sizeof(float))
            throw std::logic_error("a rank sent an image part of the wrong size");
        for (size_t local = 0; local < share.count(); local += kTile) {
            const size_t n = std::min(kTile, share.count() - local);
            std::memcpy(&rgb[share.global(local) * 3], at + local * 3 * sizeof(float), n * 3 * sizeof(float));
        }
        at += counts[static_cast<size_t>(r)];
    }
}

void scatter_image(RankExchange& ex, size_t pixels, const std::vector<float>& whole, std::vector<float>& mine,
                   Channel channel) {
    std::vector<char> all;
    std::vector<uint64_t> counts;
    constexpr size_t kTile = PixelShare::kTile;
    if (ex.rank() == 0) {
        if (whole.size() != pixels * 3) throw std::logic_error("scatter_image: not a whole image");
        for (int r = 0; r < ex.ranks(); ++r) {
            const PixelShare share{r, ex.ranks(), pixels};
            counts.push_back(share.count() * 3 * sizeof(float));
            const size_t at = all.size();
            all.resize(at + counts.back());
            for (size_t local = 0; local < share.count(); local += kTile) {
                const size_t n = std::min(kTile, share.count() - local);
                std::memcpy(all.data() + at + local * 3 * sizeof(float), &whole[share.global(local) * 3],
                            n * 3 * sizeof(float));
            }
        }
    }
    std::vector<char> part;
    ex.scatter(channel, all, counts, part);
    mine.resize(part.size() / sizeof(float));
    if (!part.empty()) std::memcpy(mine.data(), part.data(), part.size());
}

void gather_values(RankExchange& ex, std::vector<float>& values) {
    std::vector<char> all;
    std::vector<uint64_t> counts;
    ex.gather(Channel::Frames, values.data(), values.size() * sizeof(float), all, counts);
    values.resize(all.size() / sizeof(float));
    if (!all.empty()) std::memcpy(values.data(), all.data(), all.size());
}

}  // namespace sl
