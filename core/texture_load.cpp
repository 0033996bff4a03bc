#include "core/texture_load.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "config/input_file.h"
#include "config/limits.h"
#include "core/plugin.h"
#include "foundation/errors.h"

namespace sl {
namespace {

using ReadFn = int (*)(const char*, const unsigned char*, size_t, int*, int*, float**, int*, char*, size_t);

// The OpenImageIO texture plugin, loaded on first use.
ReadFn image_reader(std::string& why) {
    static const Plugin plugin = load_plugin("libslowlight_image.so", "the texture reader", {"slowlight_image_read"});
    why = plugin.error;
    return plugin.function<ReadFn>(0);
}

float srgb_to_linear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

std::shared_ptr<TextureImage> decode(const std::string& path, const unsigned char* data, size_t size,
                                     const std::string& name, bool srgb) {
    std::string why;
    ReadFn read = image_reader(why);
    if (!read) throw RuntimeFailure(name + ": " + why);
    int w = 0, h = 0, is_float = 0;
    float* rgb = nullptr;
    char error[512] = {};
    if (!read(path.c_str(), data, size, &w, &h, &rgb, &is_float, error, sizeof error)) {
        std::string msg = error;
        for (char& c : msg) if (c == '\n' || c == '\r') c = ' ';
        throw InputError(name + ": cannot read the texture" + (msg.empty() ? std::string() : ": " + msg));
    }
    auto tex = std::make_shared<TextureImage>();
    tex->width = w;
    tex->height = h;
    const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h) * 3;
    tex->rgb.assign(rgb, rgb + n);
    std::free(rgb);
    double sum[3] = {0, 0, 0};
    for (size_t i = 0; i < n; ++i) {
        float& c = tex->rgb[i];
        if (!std::isfinite(c) || c < 0) {  // textures scale albedo and emission: never negative
            c = 0;
            ++tex->replaced;
        }
        if (srgb && !is_float) c = srgb_to_linear(c);
        sum[i % 3] += c;
    }
    const double texels = static_cast<double>(n / 3);
    tex->mean = {static_cast<float>(sum[0] / texels), static_cast<float>(sum[1] / texels),
                 static_cast<float>(sum[2] / texels)};
    return tex;
}

}  // namespace

std::shared_ptr<TextureImage> load_texture_file(const std::string& path, bool srgb) {
    // The guard before the image library opens it (it opens files by name): a FIFO would block.
    check_input_file(path, limits::kMaxTextureFileBytes, path, "texture");
    return decode(path, nullptr, 0, path, srgb);
}

std::shared_ptr<TextureImage> load_texture_memory(const std::vector<unsigned char>& bytes, const std::string& name,
                                                  const std::string& format_hint, bool srgb) {
    if (bytes.empty()) throw InputError(name + ": the image holds no data");
    // OpenImageIO picks the reader by the name's extension.
    return decode("embedded." + format_hint, bytes.data(), bytes.size(), name, srgb);
}

}  // namespace sl
