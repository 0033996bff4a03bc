#include "core/plugin.h"

#include <dlfcn.h>
#include <unistd.h>

#include <climits>
#include <filesystem>

namespace sl {
namespace {

// The directory of the running executable ("" if it cannot be told).
std::filesystem::path executable_dir() {
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0) return {};
    return std::filesystem::path(std::string(exe, static_cast<size_t>(n))).parent_path();
}

// The directory of the shared object that holds this code when it is not the program (the
// Python module, whose executable is python3): its plugins are linked beside it.
std::filesystem::path own_object_dir() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&own_object_dir), &info) == 0 || !info.dli_fname) return {};
    std::error_code ec;
    const std::filesystem::path p = std::filesystem::canonical(info.dli_fname, ec);
    return ec ? std::filesystem::path() : p.parent_path();
}

}  // namespace

Plugin load_plugin(const std::string& file, const std::string& what, std::initializer_list<const char*> names,
                   PluginScope scope) {
    Plugin p;
    const int flags = RTLD_NOW | (scope == PluginScope::Global ? RTLD_GLOBAL : RTLD_LOCAL);
    // The one beside the program when it is there (its own error, not the library path's, is
    // then the one worth reporting); else whatever the library path finds.
    std::filesystem::path dir = executable_dir();
    std::error_code ec;
    bool beside = !dir.empty() && std::filesystem::exists(dir / file, ec);
    if (!beside) {
        dir = own_object_dir();
        beside = !dir.empty() && std::filesystem::exists(dir / file, ec);
    }
    void* lib = dlopen(beside ? (dir / file).c_str() : file.c_str(), flags);
    if (!lib) {
        const char* e = dlerror();
        p.error = "cannot load " + what + " " + file + ": " + (e ? e : "not found");
        return p;
    }
    for (const char* name : names) {
        void* s = dlsym(lib, name);
        if (!s) {
            p.error = what + " " + file + " has no " + name;
            return p;
        }
        p.symbols.push_back(s);
    }
    return p;
}

}  // namespace sl
