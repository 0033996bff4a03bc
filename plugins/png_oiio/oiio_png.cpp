// The PNG writer, a plugin loaded only when PNGs are asked for: OpenImageIO brings some 260
// shared libraries (~115 MiB of resident memory) that a render without --png-dir never needs.
#include <OpenImageIO/imageio.h>

#include <cstddef>
#include <cstring>
#include <mutex>
#include <string>

namespace {
void copy_error(const std::string& why, char* error, size_t size) {
    if (size == 0) return;
    std::strncpy(error, why.c_str(), size - 1);
    error[size - 1] = '\0';
}
}  // namespace

// Writes w*h*3 sRGB bytes (row 0 = top) to `path` as PNG. Returns 1, or 0 with a message.
extern "C" __attribute__((visibility("default"))) int slowlight_png_write(const char* path, int w, int h,
                                                                          const unsigned char* rgb8, char* error,
                                                                          size_t error_size) {
    // OIIO's own thread pool would compete with the renderer's TBB workers for the same cores.
    static std::once_flag once;
    std::call_once(once, [] { OIIO::attribute("threads", 1); });
    // The caller writes to a temporary name without the .png extension: name the format.
    auto out = OIIO::ImageOutput::create("png");
    if (!out) {
        copy_error(OIIO::geterror(), error, error_size);
        return 0;
    }
    const OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
    if (!(out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, rgb8) && out->close())) {
        copy_error(out->geterror(), error, error_size);
        return 0;
    }
    return 1;
}
