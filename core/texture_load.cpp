#include "core/texture_load.h"

#include <cmath>
#include <cstdlib>

#include "config/input_file.h"
#include "config/limits.h"
#include "core/plugin.h"
#include "foundation/errors.h"

namespace sl {
namespace {

using InfoFn = int (*)(const char*, const unsigned char*, size_t, int*, int*, int*, int*, int*, char*, size_t);
using RowBand = void (*)(void*, int, int, const void*);
using ReadFn = int (*)(const char*, const unsigned char*, size_t, int, RowBand, void*, char*, size_t);

// The OpenImageIO texture plugin, loaded on first use.
const Plugin& image_plugin() {
    static const Plugin plugin = load_plugin("libslowlight_image.so", "the texture reader",
                                             {"slowlight_image_info", "slowlight_image_read_rows"});
    return plugin;
}

// What the plugin opens: the file (checked first: a FIFO would block the image library, which
// opens files by name), or the bytes under a name whose extension picks the reader.
struct Opened {
    std::string path;
    const unsigned char* data = nullptr;
    size_t size = 0;
};

Opened open(const TextureSource& s) {
    if (!s.bytes) {
        check_input_file(s.path, limits::kMaxTextureFileBytes, s.path, "texture");
        return {s.path, nullptr, 0};
    }
    if (s.bytes->empty()) throw InputError(s.path + ": the image holds no data");
    return {"embedded." + s.format_hint, s.bytes->data(), s.bytes->size()};
}

[[noreturn]] void cannot_read(const TextureSource& s, const char* error) {
    std::string msg = error;
    for (char& c : msg) if (c == '\n' || c == '\r') c = ' ';
    throw InputError(s.path + ": cannot read the texture" + (msg.empty() ? std::string() : ": " + msg));
}

// Packs bands of rows into the texture's compact form and sums its mean.
struct Packer {
    TextureImage& tex;
    bool srgb_ints;  // 16-bit sRGB values: decoded to linear before they become halves
    double sum[3] = {0, 0, 0};

    void bytes(int y0, int y1, const uint8_t* rgb) {
        const ByteTable& t = ByteTable::get();
        const auto& to_linear = tex.format == TexelFormat::Srgb8 ? t.srgb : t.linear;
        const size_t first = static_cast<size_t>(y0) * static_cast<size_t>(tex.width);
        const size_t n = static_cast<size_t>(y1 - y0) * static_cast<size_t>(tex.width);
        for (size_t i = 0; i < n; ++i)
            for (size_t c = 0; c < 3; ++c) {
                tex.bytes8[(first + i) * 4 + c] = rgb[i * 3 + c];
                sum[c] += to_linear[rgb[i * 3 + c]];
            }
    }

    void floats(int y0, int y1, const float* rgb) {
        const size_t first = static_cast<size_t>(y0) * static_cast<size_t>(tex.width);
        const size_t n = static_cast<size_t>(y1 - y0) * static_cast<size_t>(tex.width) * 3;
        for (size_t i = 0; i < n; ++i) {
            float c = rgb[i];
            if (!std::isfinite(c) || c < 0) {  // textures scale albedo and emission: never negative
                c = 0;
                ++tex.replaced;
            }
            if (srgb_ints) c = srgb_to_linear(c);
            if (c > 65504.0f) {
                c = 65504.0f;
                ++tex.clamped;
            }
            const uint16_t h = float_to_half(c);
            tex.halves[first * 3 + i] = h;
            sum[i % 3] += half_to_float(h);
        }
    }

    static void band(void* self, int y0, int y1, const void* rgb) {
        auto* p = static_cast<Packer*>(self);
        if (p->tex.format == TexelFormat::Half) p->floats(y0, y1, static_cast<const float*>(rgb));
        else p->bytes(y0, y1, static_cast<const uint8_t*>(rgb));
    }
};

}  // namespace

TextureHeader probe_texture(const TextureSource& source) {
    const Plugin& plugin = image_plugin();
    if (!plugin.error.empty()) throw RuntimeFailure(source.path + ": " + plugin.error);
    const Opened o = open(source);
    int w = 0, h = 0, channels = 0, eight_bit = 0, is_float = 0;
    char error[512] = {};
    if (!plugin.function<InfoFn>(0)(o.path.c_str(), o.data, o.size, &w, &h, &channels, &eight_bit, &is_float, error,
                                    sizeof error))
        cannot_read(source, error);
    TextureHeader header{w, h, channels, TexelFormat::Half, is_float != 0};
    if (eight_bit) header.format = source.srgb ? TexelFormat::Srgb8 : TexelFormat::Linear8;
    return header;
}

std::shared_ptr<TextureImage> load_texture(const TextureSource& source) {
    const TextureHeader header = probe_texture(source);
    const Opened o = open(source);
    auto tex = std::make_shared<TextureImage>();
    tex->width = header.width;
    tex->height = header.height;
    tex->format = header.format;
    const size_t texels = static_cast<size_t>(header.width) * static_cast<size_t>(header.height);
    if (header.format == TexelFormat::Half) tex->halves.assign(texels * 3, 0);
    else tex->bytes8.assign(texels * 4, 255);
    // 16-bit and other integer images are sRGB-encoded colour when `srgb`; float images are linear.
    Packer packer{*tex, source.srgb && !header.float_values};
    char error[512] = {};
    const Plugin& plugin = image_plugin();
    if (!plugin.function<ReadFn>(1)(o.path.c_str(), o.data, o.size, header.format != TexelFormat::Half, &Packer::band,
                                    &packer, error, sizeof error))
        cannot_read(source, error);
    const double n = static_cast<double>(texels);
    tex->mean = {static_cast<float>(packer.sum[0] / n), static_cast<float>(packer.sum[1] / n),
                 static_cast<float>(packer.sum[2] / n)};
    return tex;
}

}  // namespace sl
