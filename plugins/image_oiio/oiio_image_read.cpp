// The texture reader, a plugin loaded only when a scene uses textures: OpenImageIO brings some
// 260 shared libraries (~115 MiB of resident memory) that a scene without textures never needs.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

namespace {
void copy_error(const std::string& why, char* error, size_t size) {
    if (size == 0) return;
    std::strncpy(error, why.c_str(), size - 1);
    error[size - 1] = '\0';
}
}  // namespace

// Reads an image from `path`, or from `size` bytes at `data` when data is not null (`path` then
// only names it). On success returns 1 with *rgb a malloc'ed w*h*3 float array (row 0 = top,
// values as stored: 8/16-bit formats scaled to [0,1]) and *is_float set for float formats (EXR,
// HDR), which hold linear values. Returns 0 with a message otherwise.
extern "C" __attribute__((visibility("default"))) int slowlight_image_read(
    const char* path, const unsigned char* data, size_t size, int* w, int* h, float** rgb, int* is_float,
    char* error, size_t error_size) {
    static std::once_flag once;
    std::call_once(once, [] { OIIO::attribute("threads", 1); });
    std::unique_ptr<OIIO::ImageInput> in;
    OIIO::Filesystem::IOMemReader mem(data, data ? size : 0);
    if (data) {
        OIIO::ImageSpec config;
        OIIO::Filesystem::IOProxy* proxy = &mem;
        config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
        in = OIIO::ImageInput::open(path, &config);
    } else {
        in = OIIO::ImageInput::open(path);
    }
    if (!in) {
        copy_error(OIIO::geterror(), error, error_size);
        return 0;
    }
    const OIIO::ImageSpec& spec = in->spec();
    const long long pixels = static_cast<long long>(spec.width) * spec.height;
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || pixels > (1LL << 28)) {
        copy_error("unsupported image size " + std::to_string(spec.width) + "x" + std::to_string(spec.height),
                   error, error_size);
        return 0;
    }
    const int nc = spec.nchannels;
    std::vector<float> all(static_cast<size_t>(pixels) * static_cast<size_t>(nc));
    if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, all.data())) {
        copy_error(in->geterror(), error, error_size);
        return 0;
    }
    auto* out = static_cast<float*>(std::malloc(static_cast<size_t>(pixels) * 3 * sizeof(float)));
    if (!out) {
        copy_error("out of memory", error, error_size);
        return 0;
    }
    for (long long i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) out[i * 3 + c] = all[static_cast<size_t>(i * nc + (nc >= 3 ? c : 0))];
    *w = spec.width;
    *h = spec.height;
    *rgb = out;
    *is_float = spec.format.basetype == OIIO::TypeDesc::FLOAT || spec.format.basetype == OIIO::TypeDesc::HALF ||
                spec.format.basetype == OIIO::TypeDesc::DOUBLE;
    return 1;
}
