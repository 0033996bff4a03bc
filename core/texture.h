#pragma once
// A decoded texture in the smallest form that keeps its values: 8-bit images as they are
// stored (4 bytes a texel, sRGB decoded by a table at lookup), everything else as linear half
// floats (6 bytes a texel). Row 0 at the top (glTF's UV origin), bilinear lookups with the glTF
// wrap modes. Decoding goes through the OpenImageIO plugin (core/texture_load.h).
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "config/scene_desc.h"
#include "foundation/half_float.h"

namespace sl {

enum class TexelFormat : uint8_t {
    Srgb8,    // RGBA bytes, sRGB-encoded (colour textures)
    Linear8,  // RGBA bytes, linear (data textures)
    Half,     // RGB binary16, linear
};

inline float srgb_to_linear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Byte value -> linear float: the same arithmetic as decoding the whole image to floats first.
struct ByteTable {
    std::array<float, 256> srgb, linear;
    ByteTable() {
        for (int i = 0; i < 256; ++i) {
            linear[static_cast<size_t>(i)] = static_cast<float>(i) / 255.0f;
            srgb[static_cast<size_t>(i)] = srgb_to_linear(linear[static_cast<size_t>(i)]);
        }
    }
    static const ByteTable& get() {
        static const ByteTable table;
        return table;
    }
};

struct TextureImage {
    int width = 0, height = 0;
    TexelFormat format = TexelFormat::Half;
    std::vector<uint8_t> bytes8;   // Srgb8 / Linear8: 4 per texel (alpha unused, for alignment)
    std::vector<uint16_t> halves;  // Half: 3 per texel
    Vec3 mean;                     // average texel: an emitter's power uses it
    TextureWrap wrap_s = TextureWrap::Repeat, wrap_t = TextureWrap::Repeat;
    uint64_t replaced = 0;  // channel values read as NaN, infinite or negative, drawn as 0
    uint64_t clamped = 0;   // channel values past the largest half (65504), stored as 65504

    static uint64_t texel_bytes(TexelFormat f) { return f == TexelFormat::Half ? 3 * sizeof(uint16_t) : 4; }
    uint64_t bytes() const { return bytes8.capacity() + halves.capacity() * sizeof(uint16_t); }

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
        const size_t i = static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
        if (format == TexelFormat::Half) {
            const uint16_t* p = &halves[i * 3];
            return {half_to_float(p[0]), half_to_float(p[1]), half_to_float(p[2])};
        }
        const ByteTable& t = ByteTable::get();
        const std::array<float, 256>& to_linear = format == TexelFormat::Srgb8 ? t.srgb : t.linear;
        const uint8_t* p = &bytes8[i * 4];
        return {to_linear[p[0]], to_linear[p[1]], to_linear[p[2]]};
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
