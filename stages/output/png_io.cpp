#include "stages/output/png_io.h"

#include <dlfcn.h>
#include <unistd.h>

#include <climits>
#include <filesystem>

#include "foundation/errors.h"
#include "stages/output/atomic_file.h"

namespace sl {
namespace {

using PngWriteFn = int (*)(const char*, int, int, const unsigned char*, char*, size_t);

// The OpenImageIO PNG plugin, libslowlight_png.so, beside the executable (or on the library
// path), loaded on first use.
PngWriteFn png_writer(std::string& why) {
    static std::string load_error;
    static PngWriteFn fn = [] {
        char exe[PATH_MAX];
        ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
        std::string beside = n > 0 ? (std::filesystem::path(std::string(exe, static_cast<size_t>(n))).parent_path() /
                                      "libslowlight_png.so").string()
                                   : std::string();
        void* lib = beside.empty() ? nullptr : dlopen(beside.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!lib) lib = dlopen("libslowlight_png.so", RTLD_NOW | RTLD_LOCAL);
        if (!lib) {
            const char* e = dlerror();
            load_error = "cannot load the PNG writer libslowlight_png.so: " + std::string(e ? e : "not found");
            return PngWriteFn{nullptr};
        }
        return reinterpret_cast<PngWriteFn>(dlsym(lib, "slowlight_png_write"));
    }();
    if (!fn) why = load_error.empty() ? "the PNG writer has no slowlight_png_write" : load_error;
    return fn;
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
