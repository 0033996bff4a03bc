#include "core/import/resolve_imports.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

#include "foundation/errors.h"
#include "foundation/message_lines.h"
#include "foundation/warning_lines.h"
#include "core/import/imported_file.h"
#include "core/material_stand_in.h"
#include "core/placement.h"
#include "core/texture.h"
#include "core/texture_load.h"

namespace sl {
namespace {

struct Placement {
    const ShapeDesc& s;
    Vec3 point(Vec3 p) const { return rotate_xyz(p * s.scale, s.rotate_deg) + s.translate; }
    Vec3 vector(Vec3 v) const { return rotate_xyz(v, s.rotate_deg); }
};

// Embree's BVH (high quality, robust) per triangle: 63-66 bytes measured on a 1M-triangle
// sphere (bench/bench_mesh_scale.cpp), budgeted with a margin.
constexpr uint64_t kBvhBytesPerTriangle = 100;

bool is_import(const ShapeDesc& s) { return s.type == ShapeType::Mesh || s.type == ShapeType::Gltf; }

// Camera of the first glTF import, kept between resolve_imports and imported_camera.
struct CameraNote { std::optional<CameraDesc> camera; };

// Errors name the scene file first when the mesh came through one.
ImportedFile read_file(const ShapeDesc& s, const std::string& scene_source) {
    try {
        if (s.type == ShapeType::Gltf)
            return read_gltf(s.file, s.material < 0, s.light_units.value_or(LightUnits::Photometric));
        return read_obj_mtl(s.file, s.material < 0);
    } catch (const InputError& e) {
        std::error_code ec;
        if (std::filesystem::absolute(scene_source, ec).lexically_normal().string() == s.file) throw;
        throw InputError(scene_source + ": " + e.what());
    }
}

}  // namespace

void resolve_imports(SceneDesc& scene) {
    if (scene.imports_resolved) return;
    std::set<std::string> warned;
    // The scene file's own GGX materials that a shape uses, drawn by a stand-in: one line each
    // for what that loses (core/material_stand_in.h).
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        bool used = false;
        for (const ShapeDesc& s : scene.shapes) used |= s.material == static_cast<int>(i);
        const std::string lost = used ? approximation_note(scene.materials[i]) : std::string();
        if (!lost.empty())
            emit_warning("warning: " + scene.source + ": material '" + scene.materials[i].name + "': " + lost);
    }
    std::vector<std::string> seen_files;
    for (ShapeDesc& s : scene.shapes) {
        if (!is_import(s) || s.mesh) continue;
        ImportedFile f = read_file(s, scene.source);
        const Placement place{s};
        for (const std::string& w : counted_lines(f.warnings))
            if (warned.insert(w).second) emit_warning(message_line("warning: ", w));
        // Materials: the entry's own for every triangle, or the file's (with their textures).
        std::vector<int> material_map(f.materials.size(), s.material);
        if (s.material < 0) {
            std::vector<bool> used(f.materials.size(), false);
            for (int32_t m : f.mesh.tri_material) used[static_cast<size_t>(m)] = true;
            std::vector<int> texture_map(f.textures.size(), -1);
            auto texture = [&](int local) {
                if (local < 0) return -1;
                int& g = texture_map[static_cast<size_t>(local)];
                if (g >= 0) return g;
                ImportedTexture& it = f.textures[static_cast<size_t>(local)];
                TextureDesc d = it.desc;
                auto img = it.bytes.empty() ? load_texture_file(d.file, d.srgb)
                                            : load_texture_memory(it.bytes, d.file, it.format, d.srgb);
                if (img->replaced > 0)  // said once per texture, with how many
                    emit_warning(message_line("warning: ", d.file + ": " + std::to_string(img->replaced) +
                                                               " texel values are NaN, infinite or negative: drawn as 0"));
                img->wrap_s = d.wrap_s;
                img->wrap_t = d.wrap_t;
                d.image = std::move(img);
                g = static_cast<int>(scene.textures.size());
                scene.textures.push_back(std::move(d));
                return g;
            };
            for (size_t i = 0; i < f.materials.size(); ++i) {
                if (!used[i]) continue;
                MaterialDesc m = f.materials[i];
                m.albedo_texture = texture(m.albedo_texture);
                m.metallic_roughness_texture = -1;  // not drawn yet: not decoded (the importer noted it)
                m.emission_texture = m.emits() ? texture(m.emission_texture) : -1;
                material_map[i] = static_cast<int>(scene.materials.size());
                scene.materials.push_back(std::move(m));
            }
        } else if (!f.materials.empty()) {
            // (OBJ files skip their library when the entry names a material.)
        }
        auto mesh = std::make_shared<MeshData>(std::move(f.mesh));
        for (Vec3& p : mesh->positions) {
            p = place.point(p);
            if (!is_finite(p)) throw InputError(s.file + ": a vertex is not finite once placed in the scene");
        }
        for (Vec3& n : mesh->normals) n = place.vector(n);
        for (int32_t& m : mesh->tri_material) m = material_map[static_cast<size_t>(m)];
        s.mesh = std::move(mesh);
        s.first_light = static_cast<int>(scene.lights.size());
        s.light_count = static_cast<int>(f.lights.size());
        for (LightDesc l : f.lights) {
            l.position = place.point(l.position);
            l.direction = normalize(place.vector(l.direction));
            scene.lights.push_back(l);
        }
        if (f.camera && s.type == ShapeType::Gltf) {
            CameraDesc c = *f.camera;
            Vec3 fwd = c.look_at - c.position;
            c.position = place.point(c.position);
            c.look_at = c.position + normalize(place.vector(fwd));
            c.up = normalize(place.vector(c.up));
            scene.imported_camera = c;
        }
        for (std::string& p : f.files) scene.input_files.push_back(std::move(p));
    }
    scene.imports_resolved = true;
    // A scene needs light: its own lights, or emissive triangles.
    bool lit = false;
    for (const LightDesc& l : scene.lights)
        lit |= !is_black(l.type == LightType::Quad  ? l.radiance
                        : l.type == LightType::Sun ? l.irradiance
                                                   : l.power);
    for (const ShapeDesc& s : scene.shapes)
        if (s.mesh && !lit)
            for (int32_t m : s.mesh->tri_material) if (scene.materials[static_cast<size_t>(m)].emits()) { lit = true; break; }
    if (!lit)
        throw InputError(scene.source + ": the scene has no light: no light in \"lights\", none in its imported files, "
                         "and no emissive material");
}

SceneDesc with_imports(const SceneDesc& scene) {
    SceneDesc s = scene;
    resolve_imports(s);
    return s;
}

std::optional<CameraDesc> imported_camera(const SceneDesc& scene) { return scene.imported_camera; }

uint64_t imported_mesh_bytes(const SceneDesc& scene) {
    uint64_t b = 0;
    for (const ShapeDesc& s : scene.shapes)
        if (s.mesh) b += s.mesh->bytes();
    return b;
}

uint64_t texture_bytes(const SceneDesc& scene) {
    uint64_t b = 0;
    for (const TextureDesc& t : scene.textures)
        if (t.image) b += t.image->bytes();
    return b;
}

uint64_t imported_bvh_bytes(const SceneDesc& scene) {
    uint64_t b = 0;
    for (const ShapeDesc& s : scene.shapes)
        if (s.mesh) b += s.mesh->positions.size() * 12 + s.mesh->triangle_count() * (12 + kBvhBytesPerTriangle);
    return b;
}

size_t emissive_triangles(const SceneDesc& scene) {
    size_t n = 0;
    for (const ShapeDesc& s : scene.shapes)
        if (s.mesh)
            for (int32_t m : s.mesh->tri_material) n += scene.materials[static_cast<size_t>(m)].emits();
    return n;
}

size_t imported_triangles(const SceneDesc& scene) {
    size_t n = 0;
    for (const ShapeDesc& s : scene.shapes)
        if (s.mesh) n += s.mesh->triangle_count();
    return n;
}

}  // namespace sl
