#pragma once
// What a mesh file brings into a scene before it is placed: triangles in the file's own space
// (node transforms applied), its materials, textures (not yet decoded), lights and camera.
// core/import/resolve_imports.h places it and merges it into the SceneDesc.
#include <optional>
#include <string>
#include <vector>

#include "config/scene_desc.h"
#include "core/import/mesh_data.h"
#include "core/import/mesh_instances.h"

namespace sl {

struct ImportedTexture {
    TextureDesc desc;                  // file, wrap modes, sRGB; image not decoded yet
    std::vector<unsigned char> bytes;  // encoded image inside the file (glTF), else empty
    std::string format;                // file extension naming the encoding ("png", "jpg")
};

// A mesh the file places more than once, in its own space, with its placements in the file's.
struct ImportedInstances {
    MeshData mesh;  // tri_material: index into ImportedFile::materials
    std::vector<Affine> placements;
};

struct ImportedFile {
    MeshData mesh;  // tri_material: index into materials; what the file places once
    std::vector<ImportedInstances> instanced;  // what it places more than once (glTF)
    std::vector<MaterialDesc> materials;  // albedo/emission_texture: index into textures
    std::vector<ImportedTexture> textures;
    std::vector<LightDesc> lights;
    std::optional<CameraDesc> camera;  // the first camera of the default scene (glTF)
    // The diffuse base the file's writer meant (core/import/gltf_writer_base.h); empty: default.
    std::optional<PrincipledBase> writer_principled;
    std::vector<std::string> files;    // every file read (the mesh, .mtl, .bin, images)
    std::vector<std::string> warnings;  // one line each, without the "warning: " prefix
};

// Both throw InputError naming the file (and line or element) for anything malformed. Without
// read_materials every triangle gets one default material (the scene names its own).
// `units`: how the glTF's KHR_lights_punctual intensities are read (config/scene_desc.h).
ImportedFile read_obj_mtl(const std::string& path, bool read_materials);
ImportedFile read_gltf(const std::string& path, bool read_materials, LightUnits units = LightUnits::Photometric);

}  // namespace sl
