#pragma once
// Decoding textures (PNG, JPEG, EXR, ...) through the OpenImageIO plugin, loaded on first use
// so that scenes without textures never map OpenImageIO's libraries. A texture's header is read
// first (probe_*), so that what it will cost is known before a byte of it is decoded.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/texture.h"

namespace sl {

// Where a texture's bytes come from: a file, or encoded bytes in memory (an image inside a .glb
// or a data: URI; `format_hint` is its extension, "png").
struct TextureSource {
    std::string path;                                   // the file, or the name used in messages
    const std::vector<unsigned char>* bytes = nullptr;  // in memory, or null: read `path`
    std::string format_hint;
    bool srgb = true;  // 8/16-bit values are sRGB-encoded (float formats are linear already)
};

struct TextureHeader {
    int width = 0, height = 0, channels = 0;
    TexelFormat format = TexelFormat::Half;  // what it will be held as
    bool float_values = false;               // stored as floats (linear); else integers
    uint64_t bytes() const {
        return static_cast<uint64_t>(width) * static_cast<uint64_t>(height) * TextureImage::texel_bytes(format);
    }
};

// Both throw InputError "<name>: why" when the image cannot be read.
TextureHeader probe_texture(const TextureSource& source);
std::shared_ptr<TextureImage> load_texture(const TextureSource& source);

}  // namespace sl
