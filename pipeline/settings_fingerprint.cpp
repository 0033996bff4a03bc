#include "pipeline/settings_fingerprint.h"

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string_view>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "config/input_file.h"
#include "config/scene_fields.h"
#include "foundation/xxh64.h"

namespace sl {
namespace {

constexpr uint64_t kMaxMeshBytes = uint64_t(1) << 30;  // as the mesh loader allows

// Fields that do not decide a pixel, as paths from the scene ("[]": any element of a list):
// names; file paths and decoded data, whose files' bytes are hashed instead; whether imports
// were read yet (bookkeeping); fps, which only paces the video; how an import's lights were
// read and where they went (the lights themselves are in it). Every other field of SceneDesc
// is in the fingerprint (config/scene_fields.h names them all).
constexpr std::string_view kNotPixels[] = {
    "source",        "input_files",   "imports_resolved", "materials[].name", "shapes[].file",
    "shapes[].mesh", "shapes[].instances", "textures[].file", "textures[].image", "time.fps", "shapes[].light_units",
    "shapes[].first_light", "shapes[].light_count",
};

bool decides_pixels(const std::string& path) {
    for (std::string_view p : kNotPixels)
        if (path == p) return false;
    return true;
}

// The canonical form: every field (but those above) under its name, objects with sorted keys
// (nlohmann::json keeps them so), numbers as the shortest text that reads back exactly.
struct Canonical {
    std::string path;  // where this value sits, e.g. "materials[].albedo"

    template <class T>
    nlohmann::json operator()(const T& v) const {
        if constexpr (std::is_same_v<T, Vec3>) {
            return nlohmann::json::array({v.x, v.y, v.z});
        } else if constexpr (std::is_enum_v<T>) {
            return static_cast<int>(v);
        } else if constexpr (std::is_arithmetic_v<T> || std::is_same_v<T, std::string>) {
            return v;
        } else if constexpr (requires { v.get(); }) {
            // Decoded data (a mesh, a texture's texels): its file's bytes are hashed instead,
            // and its path is in kNotPixels, so this is never reached.
            throw std::logic_error("settings fingerprint: " + path + " is not in kNotPixels");
        } else if constexpr (requires { v.has_value(); *v; }) {  // std::optional
            return v ? (*this)(*v) : nlohmann::json();
        } else if constexpr (requires { v.begin(); v.size(); }) {  // std::vector
            nlohmann::json a = nlohmann::json::array();
            for (const auto& e : v) a.push_back(Canonical{path + "[]"}(e));
            return a;
        } else {  // one of the scene's structs
            nlohmann::json o = nlohmann::json::object();
            visit_fields(v, [&](const char* name, const auto& field) {
                const std::string p = path.empty() ? std::string(name) : path + "." + name;
                if (decides_pixels(p)) o[name] = Canonical{p}(field);
            });
            return o;
        }
    }
};

}  // namespace

std::string canonical_settings(const SceneDesc& s, int sections, Strategy strategy) {
    nlohmann::json j = Canonical{}(s);
    j["sections"] = sections;
    j["strategy"] = static_cast<int>(strategy);
    return j.dump();
}

std::string settings_fingerprint(const SceneDesc& s, int sections, Strategy strategy) {
    // The bytes of every file the scene reads: the scene, meshes (also when not yet imported),
    // libraries, buffers, textures.
    Xxh64 files;
    if (!s.imports_resolved)
        for (const ShapeDesc& sh : s.shapes)
            if (sh.type == ShapeType::Mesh)  // never blindly: a FIFO or /dev/zero must not hang the run
                read_input_chunks(sh.file, kMaxMeshBytes, s.source + ": mesh '" + sh.file + "'", "mesh file",
                                  [&](const char* p, size_t n) { files.update(p, n); });
    for (const std::string& file : s.input_files)
        read_input_chunks(file, uint64_t(4) << 30, s.source + ": '" + file + "'", "input file",
                          [&](const char* p, size_t n) { files.update(p, n); });
    const std::string text = canonical_settings(s, sections, strategy) + " files " + std::to_string(files.value());
    Xxh64 h;
    h.update(text.data(), text.size());
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h.value()));
    return hex;
}

}  // namespace sl
