#include "stages/output/exr_limits.h"

#include <OpenEXR/ImfHeader.h>

#include <mutex>

#include "stages/output/exr_header_scan.h"

namespace sl {

void limit_openexr_sizes() {
    static std::once_flag once;
    std::call_once(once, [] {
        // Per side: no wider than the walk allows, no taller than its pixel count allows.
        // Tiled files are refused by the walk; a tile is held to the same bound.
        constexpr int w = static_cast<int>(kMaxExrWidth), h = static_cast<int>(kMaxExrPixels);
        Imf::Header::setMaxImageSize(w, h);
        Imf::Header::setMaxTileSize(w, h);
    });
}

}  // namespace sl
