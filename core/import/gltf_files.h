#pragma once
// The files a glTF model names (its .bin buffers and images), as tinygltf reads them through
// these callbacks: looked for in the model's own folder only (tinygltf's own lookup falls back to
// the working directory, so a missing or absolute URI could read some other file), and read
// through the regular-file and size guard (a FIFO would block, /dev/zero read forever).
// Relative paths that leave the folder ("../textures/wood.png") stay allowed: artists keep
// textures in shared folders.
#include <tiny_gltf.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

namespace sl {

class GltfFiles {
public:
    // `model_path`: the .gltf/.glb as the user named it (messages name files relative to it).
    GltfFiles(const std::string& model_path, uint64_t max_bytes);

    // The model's path for tinygltf: absolute, so that every file it looks for starts with the
    // model's folder and the working-directory candidate can be told apart and refused.
    const std::string& absolute_model_path() const { return absolute_model_; }
    tinygltf::FsCallbacks callbacks();

    // Why the last file could not be read, in our words ("" when tinygltf's message stands),
    // and why a given file (named as the user would name it) could not, if it was asked for.
    const std::string& failure() const { return failure_; }
    std::string failure_of(const std::string& shown_path) const {
        auto it = failures_.find(std::filesystem::path(shown_path).lexically_normal().string());
        return it == failures_.end() ? std::string() : it->second;
    }
    std::string shown(const std::string& path) const;  // as the user would name it

private:
    static bool exists(const std::string& path, void* self);
    static std::string expand(const std::string& path, void*) { return path; }
    static bool read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* self);
    static bool write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*);

    bool in_model_folder(const std::string& path) const { return path.rfind(folder_prefix_, 0) == 0; }
    void failed(const std::string& path, const std::string& why) {
        failure_ = why;
        failures_[std::filesystem::path(shown(path)).lexically_normal().string()] = why;
    }

    std::string absolute_model_, folder_prefix_, user_folder_;
    uint64_t max_bytes_;
    std::string failure_;
    std::map<std::string, std::string> failures_;
};

}  // namespace sl
