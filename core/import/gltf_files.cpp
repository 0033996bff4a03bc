#include "core/import/gltf_files.h"

#include <sys/stat.h>

#include <filesystem>

#include "config/input_file.h"
#include "foundation/errors.h"

namespace sl {
namespace fs = std::filesystem;

GltfFiles::GltfFiles(const std::string& model_path, uint64_t max_bytes) : max_bytes_(max_bytes) {
    std::error_code ec;
    fs::path abs = fs::absolute(fs::path(model_path), ec);
    if (ec) abs = fs::path(model_path);
    absolute_model_ = abs.lexically_normal().string();
    const std::string folder = fs::path(absolute_model_).parent_path().string();
    folder_prefix_ = folder.empty() || folder.back() != '/' ? folder + "/" : folder;
    user_folder_ = fs::path(model_path).parent_path().string();
}

tinygltf::FsCallbacks GltfFiles::callbacks() { return {&GltfFiles::exists, &GltfFiles::expand, &GltfFiles::read, &GltfFiles::write, this}; }

std::string GltfFiles::shown(const std::string& path) const {
    std::string rest = in_model_folder(path) ? path.substr(folder_prefix_.size()) : path;
    while (!rest.empty() && rest.front() == '/') rest.erase(rest.begin());
    return user_folder_.empty() ? rest : (fs::path(user_folder_) / rest).string();
}

// tinygltf asks for the model's folder first, then for ".": only the first is ours. Anything
// that exists there counts as found (the read then says what it is, rather than "missing").
bool GltfFiles::exists(const std::string& path, void* self) {
    auto& files = *static_cast<GltfFiles*>(self);
    if (!files.in_model_folder(path)) return false;
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) return true;
    files.failed(path, files.shown(path) + ": not found (a model's files are looked for in its folder only)");
    return false;
}

bool GltfFiles::read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* self) {
    auto& files = *static_cast<GltfFiles*>(self);
    out->clear();
    try {
        read_input_chunks(path, files.max_bytes_, files.shown(path), "file a glTF model names",
                          [&](const char* data, size_t n) { out->insert(out->end(), data, data + n); });
    } catch (const InputError& e) {
        files.failed(path, e.what());
        if (err) *err += files.failure_;
        out->clear();
        return false;
    }
    files.failure_.clear();
    return true;
}

// Reading a model never writes a file.
bool GltfFiles::write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "writing is not allowed";
    return false;
}

}  // namespace sl
