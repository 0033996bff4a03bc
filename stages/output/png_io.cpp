#include "stages/output/png_io.h"

#include "core/plugin.h"
#include "foundation/errors.h"
#include "stages/output/atomic_file.h"

namespace sl {
namespace {

using PngWriteFn = int (*)(const char*, int, int, const unsigned char*, char*, size_t);

// The OpenImageIO PNG plugin, loaded on first use.
PngWriteFn png_writer(std::string& why) {
    static const Plugin plugin = load_plugin("libslowlight_png.so", "the PNG writer", {"slowlight_png_write"});
    why = plugin.error;
    return plugin.function<PngWriteFn>(0);
}

}  // namespace

void write_png(const std::string& path, int w, int h, const uint8_t* rgb8) {
    auto fail = [&](const std::string& why) {
        return RuntimeFailure(one_line("cannot write PNG '" + path + "': " + why));
    };
    if (w <= 0 || h <= 0) throw fail("empty image");
    std::string why;
    PngWriteFn write = png_writer(why);
    if (!write) throw fail(why);
    const std::string temp = temp_sibling(path);
    char error[512] = {};
    if (!write(temp.c_str(), w, h, rgb8, error, sizeof error)) {
        discard_file(temp);
        throw fail(error);
    }
    commit_file(temp, path);
}

}  // namespace sl
