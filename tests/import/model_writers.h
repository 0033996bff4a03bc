#pragma once
// Writes small OBJ+MTL and glTF (.gltf + .bin, or .glb) files from quads and triangles, so that
// the import tests make their own assets in a temporary folder.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "config/scene_desc.h"

namespace sl::test {

struct ModelMaterial {
    ModelMaterial(std::string n, Vec3 a, Vec3 e = Vec3(0), std::string image = "")
        : name(std::move(n)), albedo(a), emission(e), albedo_image(std::move(image)) {}
    std::string name;
    Vec3 albedo{0.8f};
    Vec3 emission;             // W sr^-1 m^-2
    std::string albedo_image;  // texture file name beside the model, or empty
    bool double_sided = false;
    // glTF only. The defaults write the matte material below (no specular layer).
    float metallic = 0, roughness = 1, specular = 0;
    std::string metallic_roughness_image;  // linear: G roughness, B metallic
    std::string normal_image;              // tangent-space normal map
    float normal_scale = 1;
};

// Triangles (counter-clockwise from the front) with optional per-vertex normals and UVs.
struct ModelMesh {
    std::vector<Vec3> positions, normals;
    std::vector<float> uvs;  // glTF convention: v = 0 at the image's top
    std::vector<float> tangents;  // glTF only: 4 per vertex (xyz, handedness w), or empty
    std::vector<uint32_t> indices;
    std::vector<int> tri_material;

    // corner, corner + e1, corner + e1 + e2, corner + e2: front = e1 x e2.
    void quad(Vec3 c, Vec3 e1, Vec3 e2, int material) {
        auto b = static_cast<uint32_t>(positions.size());
        positions.insert(positions.end(), {c, c + e1, c + e1 + e2, c + e2});
        uvs.insert(uvs.end(), {0, 1, 1, 1, 1, 0, 0, 0});
        Vec3 n = normalize(cross(e1, e2));
        normals.insert(normals.end(), {n, n, n, n});
        indices.insert(indices.end(), {b, b + 1, b + 2, b, b + 2, b + 3});
        tri_material.insert(tri_material.end(), {material, material});
    }
    // The six faces of an axis-aligned box, facing out (as the scene JSON's box).
    void box(Vec3 lo, Vec3 hi, int material) {
        Vec3 d = hi - lo, ex{d.x, 0, 0}, ey{0, d.y, 0}, ez{0, 0, d.z};
        quad(lo, ey, ex, material);
        quad(lo + ez, ex, ey, material);
        quad(lo, ez, ey, material);
        quad(lo + ex, ey, ez, material);
        quad(lo, ex, ez, material);
        quad(lo + ey, ez, ex, material);
    }
};

inline void write_obj(const std::string& obj_path, const std::string& mtl_name, const ModelMesh& m,
                      const std::vector<ModelMaterial>& mats, bool with_normals = true) {
    std::ofstream o(obj_path);
    o.precision(9);
    o << "mtllib " << mtl_name << "\n";
    for (Vec3 p : m.positions) o << "v " << p.x << ' ' << p.y << ' ' << p.z << "\n";
    for (size_t i = 0; i < m.positions.size(); ++i) o << "vt " << m.uvs[2 * i] << ' ' << 1 - m.uvs[2 * i + 1] << "\n";
    if (with_normals)
        for (Vec3 n : m.normals) o << "vn " << n.x << ' ' << n.y << ' ' << n.z << "\n";
    int current = -1;
    for (size_t t = 0; t < m.tri_material.size(); ++t) {
        if (m.tri_material[t] != current) {
            current = m.tri_material[t];
            o << "usemtl " << mats[static_cast<size_t>(current)].name << "\n";
        }
        o << "f";
        for (int k = 0; k < 3; ++k) {
            uint32_t i = m.indices[3 * t + k] + 1;
            o << ' ' << i << '/' << i;
            if (with_normals) o << '/' << i;
        }
        o << "\n";
    }
    std::ofstream l((std::filesystem::path(obj_path).parent_path() / mtl_name).string());
    l.precision(9);
    for (const ModelMaterial& mat : mats) {
        l << "newmtl " << mat.name << "\nKd " << mat.albedo.x << ' ' << mat.albedo.y << ' ' << mat.albedo.z << "\n";
        if (!is_black(mat.emission)) l << "Ke " << mat.emission.x << ' ' << mat.emission.y << ' ' << mat.emission.z << "\n";
        if (!mat.albedo_image.empty()) l << "map_Kd " << mat.albedo_image << "\n";
    }
}

// glTF with one mesh (a primitive per material) under one node; binary = .glb. generator:
// asset.generator (the writer's name), left out when empty.
inline void write_gltf(const std::string& path, const ModelMesh& m, const std::vector<ModelMaterial>& mats, bool binary,
                       const nlohmann::json& extra_lights = nullptr, const std::string& generator = "") {
    using nlohmann::json;
    std::vector<unsigned char> bin;
    auto append = [&](const void* p, size_t n) {
        size_t off = bin.size();
        bin.resize(off + n);
        std::memcpy(bin.data() + off, p, n);
        while (bin.size() % 4) bin.push_back(0);
        return off;
    };
    json j;
    j["asset"] = {{"version", "2.0"}};
    if (!generator.empty()) j["asset"]["generator"] = generator;
    j["scene"] = 0;
    j["scenes"] = json::array({{{"nodes", {0}}}});
    j["nodes"] = json::array({{{"mesh", 0}}});
    json views = json::array(), accessors = json::array(), prims = json::array(), materials = json::array(),
         textures = json::array(), images = json::array();
    auto view = [&](size_t off, size_t len) {
        views.push_back({{"buffer", 0}, {"byteOffset", off}, {"byteLength", len}});
        return views.size() - 1;
    };
    size_t n = m.positions.size();
    Vec3 lo(1e30f), hi(-1e30f);
    for (Vec3 p : m.positions) { lo = vmin(lo, p); hi = vmax(hi, p); }
    size_t pv = view(append(m.positions.data(), n * 12), n * 12);
    accessors.push_back({{"bufferView", pv}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"},
                         {"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}});
    size_t nv = view(append(m.normals.data(), n * 12), n * 12);
    accessors.push_back({{"bufferView", nv}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}});
    size_t tv = view(append(m.uvs.data(), n * 8), n * 8);
    accessors.push_back({{"bufferView", tv}, {"componentType", 5126}, {"count", n}, {"type", "VEC2"}});
    json attributes = {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}};
    if (!m.tangents.empty()) {
        size_t gv = view(append(m.tangents.data(), n * 16), n * 16);
        accessors.push_back({{"bufferView", gv}, {"componentType", 5126}, {"count", n}, {"type", "VEC4"}});
        attributes["TANGENT"] = accessors.size() - 1;
    }
    for (size_t mi = 0; mi < mats.size(); ++mi) {
        std::vector<uint32_t> idx;
        for (size_t t = 0; t < m.tri_material.size(); ++t)
            if (m.tri_material[t] == static_cast<int>(mi))
                idx.insert(idx.end(), {m.indices[3 * t], m.indices[3 * t + 1], m.indices[3 * t + 2]});
        const ModelMaterial& mat = mats[mi];
        // Matte, as glTF can say it: no specular layer (KHR_materials_specular's factor 0) leaves
        // the metallic-roughness material's Lambertian base alone, which the tests compare with
        // a scene file's diffuse material.
        json jm = {{"name", mat.name},
                   {"pbrMetallicRoughness", {{"baseColorFactor", {mat.albedo.x, mat.albedo.y, mat.albedo.z, 1.0}},
                                             {"metallicFactor", mat.metallic}, {"roughnessFactor", mat.roughness}}},
                   {"doubleSided", mat.double_sided},
                   {"extensions", {{"KHR_materials_specular", {{"specularFactor", mat.specular}}}}}};
        if (!is_black(mat.emission)) {
            float s = max_component(mat.emission);
            jm["emissiveFactor"] = {mat.emission.x / s, mat.emission.y / s, mat.emission.z / s};
            jm["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", s}};
        }
        auto texture = [&](const std::string& image) {
            if (binary) {  // a .glb carries its images in its buffer
                std::ifstream in((std::filesystem::path(path).parent_path() / image).string(), std::ios::binary);
                std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
                size_t iv = view(append(bytes.data(), bytes.size()), bytes.size());
                images.push_back({{"bufferView", iv}, {"mimeType", "image/png"}});
            } else {
                images.push_back({{"uri", image}});
            }
            textures.push_back({{"source", images.size() - 1}});
            return textures.size() - 1;
        };
        if (!mat.albedo_image.empty())
            jm["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", texture(mat.albedo_image)}};
        if (!mat.metallic_roughness_image.empty())
            jm["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {{"index", texture(mat.metallic_roughness_image)}};
        if (!mat.normal_image.empty())
            jm["normalTexture"] = {{"index", texture(mat.normal_image)}, {"scale", mat.normal_scale}};
        materials.push_back(jm);
        if (idx.empty()) continue;
        size_t iv = view(append(idx.data(), idx.size() * 4), idx.size() * 4);
        accessors.push_back({{"bufferView", iv}, {"componentType", 5125}, {"count", idx.size()}, {"type", "SCALAR"}});
        prims.push_back({{"attributes", attributes},
                         {"indices", accessors.size() - 1}, {"material", mi}});
    }
    j["meshes"] = json::array({{{"primitives", prims}}});
    j["materials"] = materials;
    if (!images.empty()) { j["images"] = images; j["textures"] = textures; }
    j["bufferViews"] = views;
    j["accessors"] = accessors;
    j["extensionsUsed"] = {"KHR_materials_emissive_strength", "KHR_materials_specular"};
    if (!extra_lights.is_null()) {
        j["extensionsUsed"].push_back("KHR_lights_punctual");
        j["extensions"] = {{"KHR_lights_punctual", {{"lights", extra_lights["lights"]}}}};
        for (const auto& node : extra_lights["nodes"]) {
            j["nodes"].push_back(node);
            j["scenes"][0]["nodes"].push_back(j["nodes"].size() - 1);
        }
    }
    if (!binary) {
        std::string bin_name = std::filesystem::path(path).stem().string() + ".bin";
        j["buffers"] = json::array({{{"uri", bin_name}, {"byteLength", bin.size()}}});
        std::ofstream(path) << j.dump();
        std::ofstream b((std::filesystem::path(path).parent_path() / bin_name).string(), std::ios::binary);
        b.write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
        return;
    }
    j["buffers"] = json::array({{{"byteLength", bin.size()}}});
    std::string text = j.dump();
    while (text.size() % 4) text.push_back(' ');
    auto u32 = [](std::ofstream& o, uint32_t v) { o.write(reinterpret_cast<const char*>(&v), 4); };
    std::ofstream o(path, std::ios::binary);
    o.write("glTF", 4);
    u32(o, 2);
    u32(o, static_cast<uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
    u32(o, static_cast<uint32_t>(text.size()));
    o.write("JSON", 4);
    o.write(text.data(), static_cast<std::streamsize>(text.size()));
    u32(o, static_cast<uint32_t>(bin.size()));
    o.write("BIN\0", 4);
    o.write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
}

// The scene shape that imports a model file (its own materials: material -1).
inline ShapeDesc model_shape(const std::string& file, ShapeType type = ShapeType::Mesh) {
    ShapeDesc sh;
    sh.type = type;
    sh.file = file;
    sh.material = -1;
    return sh;
}

}  // namespace sl::test
