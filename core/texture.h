#pragma once
// A decoded texture: linear RGB floats, row 0 at the top (glTF's UV origin), bilinear lookups
// with the glTF wrap modes. Decoding goes through the OpenImageIO plugin (core/texture_load.h).
#include <cmath>
#include <cstdint>
#include <vector>

#include "config/scene_desc.h"

namespace sl {

struct TextureImage {
    int width = 0, height = 0;
    std::vector<float> rgb;  // 3 per texel, linear
    Vec3 mean;               // average texel: an emitter's power uses it
    TextureWrap wrap_s = TextureWrap::Repeat, wrap_t = TextureWrap::Repeat;
    uint64_t replaced = 0;  // channel values read as NaN, infinite or negative, drawn as 0

    uint64_t bytes() const { return rgb.capacity() * sizeof(float); }

    // Bilinear filtering between texel centres, at (u, v) with v = 0 at the top row.
    Vec3 sample(float u, float v) const {
        float x = u * static_cast<float>(width) - 0.5f, y = v * static_cast<float>(height) - 0.5f;
        float fx = std::floor(x), fy = std::floor(y);
        float ax = x - fx, ay = y - fy;
        int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
        int xa = wrap(x0, width, wrap_s), xb = wrap(x0 + 1, width, wrap_s);
        int ya = wrap(y0, height, wrap_t), yb = wrap(y0 + 1, height, wrap_t);
        return texel(xa, ya) * ((1 - ax) * (1 - ay)) + texel(xb, ya) * (ax * (1 - ay)) +
               texel(xa, yb) * ((1 - ax) * ay) + texel(xb, yb) * (ax * ay);
    }

    Vec3 texel(int x, int y) const {
        const float* p = &rgb[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 3];
        return {p[0], p[1], p[2]};
    }

    static int wrap(int i, int n, TextureWrap mode) {
        if (!(i >= -(1 << 30) && i <= (1 << 30))) i = 0;  // NaN or huge UVs: any texel will do
        switch (mode) {
            case TextureWrap::Clamp: return i < 0 ? 0 : (i >= n ? n - 1 : i);
            case TextureWrap::MirroredRepeat: {
                int period = 2 * n, m = ((i % period) + period) % period;
                return m < n ? m : period - 1 - m;
            }
            case TextureWrap::Repeat: break;
        }
        return ((i % n) + n) % n;
    }
};

}  // namespace sl
