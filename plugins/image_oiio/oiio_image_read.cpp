// The texture reader, a plugin loaded only when a scene uses textures: OpenImageIO brings some
// 260 shared libraries (~115 MiB of resident memory) that a scene without textures never needs.
// Two entry points: the header alone (so that the memory plan can count a texture before it is
// decoded) and the pixels, handed over a band of rows at a time (so that a 16K texture never
// exists as floats: the caller packs each band into its compact texel format).
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

namespace {

// The largest image read: 2^28 texels (16384²), about 1 GiB as 8-bit RGBA.
constexpr long long kMaxTexels = 1LL << 28;
// Bytes of one band of rows handed to the caller.
constexpr size_t kBandBytes = 8u << 20;

void copy_error(const std::string& why, char* error, size_t size) {
    if (size == 0) return;
    std::strncpy(error, why.c_str(), size - 1);
    error[size - 1] = '\0';
}

struct Opened {
    OIIO::Filesystem::IOMemReader mem;
    std::unique_ptr<OIIO::ImageInput> in;
    Opened(const char* path, const unsigned char* data, size_t size) : mem(data, data ? size : 0) {
        static std::once_flag once;
        std::call_once(once, [] { OIIO::attribute("threads", 1); });
        if (data) {
            OIIO::ImageSpec config;
            OIIO::Filesystem::IOProxy* proxy = &mem;
            config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
            in = OIIO::ImageInput::open(path, &config);
        } else {
            in = OIIO::ImageInput::open(path);
        }
    }
};

bool is_float(const OIIO::ImageSpec& spec) {
    const auto t = spec.format.basetype;
    return t == OIIO::TypeDesc::FLOAT || t == OIIO::TypeDesc::HALF || t == OIIO::TypeDesc::DOUBLE;
}

bool usable(const OIIO::ImageSpec& spec, char* error, size_t error_size) {
    const long long texels = static_cast<long long>(spec.width) * spec.height;
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || texels > kMaxTexels) {
        copy_error("unsupported image size " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                       " (at most 268435456 texels, 16384x16384)",
                   error, error_size);
        return false;
    }
    return true;
}

}  // namespace

// The header of an image at `path`, or of `size` bytes at `data` when data is not null (`path`
// then only names it): width, height, channels, and whether its values are 8-bit (*eight_bit)
// or floats (*is_float; both 0: 16-bit or other integers). Returns 1, or 0 with a message.
extern "C" __attribute__((visibility("default"))) int slowlight_image_info(
    const char* path, const unsigned char* data, size_t size, int* w, int* h, int* channels, int* eight_bit,
    int* is_float_out, char* error, size_t error_size) {
    Opened o(path, data, size);
    if (!o.in) {
        copy_error(OIIO::geterror(), error, error_size);
        return 0;
    }
    const OIIO::ImageSpec& spec = o.in->spec();
    if (!usable(spec, error, error_size)) return 0;
    *w = spec.width;
    *h = spec.height;
    *channels = spec.nchannels;
    *eight_bit = spec.format.basetype == OIIO::TypeDesc::UINT8 || spec.format.basetype == OIIO::TypeDesc::INT8;
    *is_float_out = is_float(spec);
    return 1;
}

// Called with rows [y0, y1) of RGB: `as_bytes` = 1 for uint8 values as stored, else floats
// (integer formats scaled to [0, 1]), 3 per texel, row 0 at the top.
using RowBand = void (*)(void* ctx, int y0, int y1, const void* rgb);

// Reads the image in bands of rows, each handed to `band`. 8-bit images are read as bytes
// (`as_bytes` 1), others as floats. The first three channels are read (one channel: grey,
// copied to all three). Returns 1, or 0 with a message (the caller discards the bands it had).
extern "C" __attribute__((visibility("default"))) int slowlight_image_read_rows(
    const char* path, const unsigned char* data, size_t size, int as_bytes, RowBand band, void* ctx, char* error,
    size_t error_size) {
    Opened o(path, data, size);
    if (!o.in) {
        copy_error(OIIO::geterror(), error, error_size);
        return 0;
    }
    const OIIO::ImageSpec spec = o.in->spec();
    if (!usable(spec, error, error_size)) return 0;
    const int read_channels = std::min(spec.nchannels, 3);
    const OIIO::TypeDesc type = as_bytes ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
    const size_t value = as_bytes ? 1 : sizeof(float);
    const size_t row_in = static_cast<size_t>(spec.width) * static_cast<size_t>(read_channels) * value;
    const size_t row_out = static_cast<size_t>(spec.width) * 3 * value;
    const int rows = static_cast<int>(std::max<size_t>(1, kBandBytes / row_out));
    std::vector<unsigned char> in(row_in * static_cast<size_t>(rows)), out(row_out * static_cast<size_t>(rows));
    for (int y0 = 0; y0 < spec.height; y0 += rows) {
        const int y1 = std::min(spec.height, y0 + rows);
        if (!o.in->read_scanlines(0, 0, y0 + spec.y, y1 + spec.y, 0, 0, read_channels, type, in.data())) {
            copy_error(o.in->geterror(), error, error_size);
            return 0;
        }
        const size_t texels = static_cast<size_t>(y1 - y0) * static_cast<size_t>(spec.width);
        for (size_t i = 0; i < texels; ++i)
            for (int c = 0; c < 3; ++c)
                std::memcpy(&out[(i * 3 + static_cast<size_t>(c)) * value],
                            &in[(i * static_cast<size_t>(read_channels) + static_cast<size_t>(read_channels == 3 ? c : 0)) * value], value);
        band(ctx, y0, y1, out.data());
    }
    return 1;
}
