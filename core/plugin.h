#pragma once
// One way to load our plugins (plugins/: the PNG writer, the texture reader, the time label,
// MPI): the shared object beside the executable if it is there, else by name on the library
// path; then its entry points by name, with one clear message for whatever is missing.
// Plugins are loaded on first use so that a plain render never maps their libraries.
#include <initializer_list>
#include <string>
#include <vector>

namespace sl {

enum class PluginScope {
    Local,   // its symbols stay its own
    Global,  // they join the global scope (MPI's components, loaded by MPI_Init, look there)
};

struct Plugin {
    std::vector<void*> symbols;  // one per name asked for, all non-null when `error` is empty
    std::string error;           // "cannot load the PNG writer libslowlight_png.so: ..." or "... has no NAME"

    template <class Fn>
    Fn function(size_t i) const {
        return error.empty() ? reinterpret_cast<Fn>(symbols[i]) : nullptr;
    }
};

// Loads `file` (e.g. "libslowlight_png.so"; `what` names it in messages: "the PNG writer") and
// looks up `names`. Never throws: the caller decides what a missing plugin means.
Plugin load_plugin(const std::string& file, const std::string& what, std::initializer_list<const char*> names,
                   PluginScope scope = PluginScope::Local);

}  // namespace sl
