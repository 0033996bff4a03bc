#include "core/import/resolve_imports.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <tuple>
#include <unistd.h>

#include "foundation/byte_sizes.h"
#include "foundation/errors.h"
#include "foundation/message_lines.h"
#include "foundation/warning_lines.h"
#include "core/import/imported_file.h"
#include "core/import/mesh_instances.h"
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
// Embree's instance (its geometry object, transforms and top-level BVH entry) and ours (the
// normal matrix and per-geometry tables), budgeted with a margin (measured: docs/scenes.md).
constexpr uint64_t kBytesPerInstance = 1024;

// The entry's scale, rotation and translation as one transform.
Affine entry_affine(const ShapeDesc& s) {
    Affine a;
    for (int c = 0; c < 3; ++c) {
        Vec3 e(0);
        e[c] = s.scale;
        const Vec3 col = rotate_xyz(e, s.rotate_deg);
        a.m[c] = col.x;
        a.m[4 + c] = col.y;
        a.m[8 + c] = col.z;
    }
    a.m[3] = s.translate.x;
    a.m[7] = s.translate.y;
    a.m[11] = s.translate.z;
    return a;
}

// Entries that name the same file the same way share what it holds: read once, placed by
// instances. (Their own material, if they name one, is part of the way, and so are the light
// units and the diffuse base their materials are drawn with.)
using FileKey = std::tuple<int, std::string, int, int, int>;
FileKey key_of(const ShapeDesc& s) {
    return {static_cast<int>(s.type), s.file, s.material, s.light_units ? static_cast<int>(*s.light_units) : -1,
            s.principled ? static_cast<int>(*s.principled) : -1};  // unset: the file's writer decides
}

// What a mesh holds once built: its arrays, Embree's copy of vertices and indices, its BVH.
uint64_t built_bytes(const MeshData& m) {
    return m.bytes() + m.positions.size() * 12 + m.triangle_count() * (12 + kBvhBytesPerTriangle);
}

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


std::vector<bool> used_materials(const ImportedFile& f) {
    std::vector<bool> used(f.materials.size(), false);
    for (int32_t m : f.mesh.tri_material) used[static_cast<size_t>(m)] = true;
    for (const ImportedInstances& in : f.instanced)
        for (int32_t m : in.mesh.tri_material) used[static_cast<size_t>(m)] = true;
    return used;
}

TextureSource source_of(const ImportedTexture& t) {
    return {t.desc.file, t.bytes.empty() ? nullptr : &t.bytes, t.format, t.desc.srgb};
}

// The headers of the textures a file's used materials draw (empty entries for the others).
std::vector<TextureHeader> texture_headers(const ShapeDesc& s, const ImportedFile& f) {
    std::vector<TextureHeader> headers(f.textures.size());
    if (s.material >= 0) return headers;
    const std::vector<bool> used = used_materials(f);
    std::vector<bool> probed(f.textures.size(), false);
    auto probe = [&](int t) {
        if (t < 0 || probed[static_cast<size_t>(t)]) return;
        probed[static_cast<size_t>(t)] = true;
        headers[static_cast<size_t>(t)] = probe_texture(source_of(f.textures[static_cast<size_t>(t)]));
    };
    for (size_t i = 0; i < f.materials.size(); ++i)
        if (used[i]) {
            probe(f.materials[i].albedo_texture);
            probe(f.materials[i].metallic_roughness_texture);
            probe(f.materials[i].normal_texture);
            if (f.materials[i].emits()) probe(f.materials[i].emission_texture);
        }
    return headers;
}

uint64_t machine_bytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page > 0 ? static_cast<uint64_t>(pages) * static_cast<uint64_t>(page) : 0;
}

// Meshes (as parsed, plus Embree's copy and BVH) and textures (as they will be held) against the
// budget, before any texture is decoded.
void check_budget(const std::vector<std::pair<ShapeDesc*, ImportedFile>>& files,
                  const std::vector<std::vector<ShapeDesc*>>& users,
                  const std::vector<std::vector<TextureHeader>>& headers, const ImportBudget& budget,
                  const std::string& source) {
    uint64_t meshes = 0, textures = 0, largest = 0;
    std::string largest_name;
    for (size_t i = 0; i < files.size(); ++i) {
        // Each mesh once, however many entries and nodes place it, plus a transform per copy.
        const ImportedFile& f = files[i].second;
        const uint64_t n = users[i].size();
        meshes += built_bytes(f.mesh) + (n > 1 ? n * kBytesPerInstance : 0);
        for (const ImportedInstances& in : f.instanced)
            meshes += built_bytes(in.mesh) + n * in.placements.size() * (sizeof(Affine) + kBytesPerInstance);
        for (size_t t = 0; t < headers[i].size(); ++t) {
            const TextureHeader& h = headers[i][t];
            textures += h.bytes();
            if (h.bytes() > largest) {
                largest = h.bytes();
                largest_name = files[i].second.textures[t].desc.file + " (" + std::to_string(h.width) + "x" +
                               std::to_string(h.height) + ", " + format_bytes(h.bytes()) + ")";
            }
        }
    }
    const uint64_t bound = budget.bytes ? budget.bytes : machine_bytes();
    if (bound == 0 || meshes + textures <= bound) return;
    std::string what = budget.bytes ? budget.what : "this machine's " + format_bytes(bound);
    throw InputError(source + ": the imported models need " + format_bytes(meshes + textures) + " (meshes and BVH " +
                     format_bytes(meshes) + ", textures " + format_bytes(textures) +
                     (largest_name.empty() ? std::string() : ", the largest " + largest_name) + "), more than " + what +
                     "; nothing was decoded");
}
}  // namespace

void resolve_imports(SceneDesc& scene, const ImportBudget& budget) {
    if (scene.imports_resolved) return;
    std::set<std::string> warned;
    // Every file parsed first (once, however many entries name it), and the headers of the
    // textures its materials use: what the imports will hold is known before a texel is decoded.
    std::vector<std::pair<ShapeDesc*, ImportedFile>> files;
    std::vector<std::vector<ShapeDesc*>> users;  // per file: the entries that place it
    std::map<FileKey, size_t> file_of;
    for (ShapeDesc& s : scene.shapes) {
        if (!is_import(s) || s.mesh) continue;
        auto [it, fresh] = file_of.try_emplace(key_of(s), files.size());
        if (fresh) {
            files.emplace_back(&s, read_file(s, scene.source));
            users.emplace_back();
        }
        users[it->second].push_back(&s);
    }
    std::vector<std::vector<TextureHeader>> headers;
    for (auto& [s, f] : files) headers.push_back(texture_headers(*s, f));
    check_budget(files, users, headers, budget, scene.source);
    const auto nothing_baked = std::make_shared<const MeshData>();

    for (size_t fi = 0; fi < files.size(); ++fi) {
        const ShapeDesc& first = *files[fi].first;
        ImportedFile& f = files[fi].second;
        for (const std::string& w : counted_lines(f.warnings))
            if (warned.insert(w).second) emit_warning(message_line("warning: ", w));
        // Materials: the entry's own for every triangle, or the file's (with their textures).
        std::vector<int> material_map(f.materials.size(), first.material);
        if (first.material < 0) {
            const std::vector<bool> used = used_materials(f);
            std::vector<int> texture_map(f.textures.size(), -1);
            auto texture = [&](int local) {
                if (local < 0) return -1;
                int& g = texture_map[static_cast<size_t>(local)];
                if (g >= 0) return g;
                ImportedTexture& it = f.textures[static_cast<size_t>(local)];
                TextureDesc d = it.desc;
                auto img = load_texture(source_of(it));
                if (img->replaced > 0)  // said once per texture, with how many
                    emit_warning(message_line("warning: ", d.file + ": " + std::to_string(img->replaced) +
                                                               " texel values are NaN, infinite or negative: drawn as 0"));
                if (img->clamped > 0)
                    emit_warning(message_line("warning: ", d.file + ": " + std::to_string(img->clamped) +
                                                               " texel values are above 65504 (the largest half float): drawn as 65504"));
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
                // The entry's choice of diffuse base (a gltf's "principled", --gltf-principled),
                // else the one the file's writer meant (Blender 3.x: its Principled v1).
                if (m.type == MaterialType::MetallicRoughness && first.type == ShapeType::Gltf)
                    m.principled = first.principled.value_or(f.writer_principled.value_or(PrincipledBase::EnergyConserving));
                m.albedo_texture = texture(m.albedo_texture);
                m.metallic_roughness_texture = texture(m.metallic_roughness_texture);
                m.normal_texture = texture(m.normal_texture);
                m.emission_texture = m.emits() ? texture(m.emission_texture) : -1;
                material_map[i] = static_cast<int>(scene.materials.size());
                scene.materials.push_back(std::move(m));
            }
        } else if (!f.materials.empty()) {
            // (OBJ files skip their library when the entry names a material.)
        }
        for (int32_t& m : f.mesh.tri_material) m = material_map[static_cast<size_t>(m)];
        // Hits on a mesh carry a tangent frame when one of its materials draws a normal map.
        auto mark_tangent_frames = [&](MeshData& mesh) {
            for (int32_t m : mesh.tri_material)
                if (scene.materials[static_cast<size_t>(m)].normal_texture >= 0) {
                    mesh.tangent_frames = !mesh.uvs.empty();
                    break;
                }
        };
        mark_tangent_frames(f.mesh);
        std::vector<InstancedMesh> prototypes;  // the file's own instanced meshes, placed in the file
        for (ImportedInstances& in : f.instanced) {
            for (int32_t& m : in.mesh.tri_material) m = material_map[static_cast<size_t>(m)];
            mark_tangent_frames(in.mesh);
            prototypes.push_back({std::make_shared<const MeshData>(std::move(in.mesh)), std::move(in.placements)});
        }
        const std::vector<ShapeDesc*>& placing = users[fi];
        // Placed once: baked into scene space, as it always was. Placed by several entries:
        // held once in the file's space, each entry an instance of it.
        std::shared_ptr<const MeshData> shared_mesh;
        if (placing.size() > 1 && f.mesh.triangle_count() > 0)
            shared_mesh = std::make_shared<const MeshData>(std::move(f.mesh));
        for (ShapeDesc* sp : placing) {
            ShapeDesc& s = *sp;
            const Placement place{s};
            const Affine entry = entry_affine(s);
            auto instances = std::make_shared<InstancedMeshes>();
            auto add = [&](const std::shared_ptr<const MeshData>& mesh, const std::vector<Affine>& in_file) {
                InstancedMesh im{mesh, {}};
                Vec3 lo(1e30f), hi(-1e30f);
                for (Vec3 p : mesh->positions) { lo = vmin(lo, p); hi = vmax(hi, p); }
                for (const Affine& a : in_file) {
                    const Affine placed = entry.after(a);
                    // The box's corners hold the largest coordinates any vertex reaches.
                    for (int k = 0; k < 8; ++k)
                        if (!is_finite(placed.point({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z})))
                            throw InputError(s.file + ": a vertex is not finite once placed in the scene");
                    im.placements.push_back(placed);
                }
                instances->meshes.push_back(std::move(im));
            };
            if (shared_mesh) add(shared_mesh, {Affine{}});
            for (const InstancedMesh& p : prototypes) add(p.mesh, p.placements);
            if (placing.size() > 1) {
                s.mesh = nothing_baked;
            } else {
                auto mesh = std::make_shared<MeshData>(std::move(f.mesh));
                for (Vec3& p : mesh->positions) {
                    p = place.point(p);
                    if (!is_finite(p)) throw InputError(s.file + ": a vertex is not finite once placed in the scene");
                }
                for (Vec3& n : mesh->normals) n = place.vector(n);
                for (size_t i = 0; i + 3 < mesh->tangents.size(); i += 4) {
                    const Vec3 t = place.vector({mesh->tangents[i], mesh->tangents[i + 1], mesh->tangents[i + 2]});
                    mesh->tangents[i] = t.x, mesh->tangents[i + 1] = t.y, mesh->tangents[i + 2] = t.z;
                }
                s.mesh = std::move(mesh);
            }
            if (!instances->meshes.empty()) s.instances = std::move(instances);
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
            for (const std::string& p : f.files) scene.input_files.push_back(p);
        }
    }
    scene.imports_resolved = true;
    // A scene needs light: its own lights, or emissive triangles.
    bool lit = false;
    for (const LightDesc& l : scene.lights)
        lit |= !is_black(l.type == LightType::Quad  ? l.radiance
                        : l.type == LightType::Sun ? l.irradiance
                                                   : l.power);
    auto emits = [&](const MeshData& m) {
        for (int32_t t : m.tri_material)
            if (scene.materials[static_cast<size_t>(t)].emits()) return true;
        return false;
    };
    for (const ShapeDesc& s : scene.shapes) {
        if (lit) break;
        if (s.mesh) lit = emits(*s.mesh);
        if (s.instances)
            for (const InstancedMesh& im : s.instances->meshes) lit = lit || emits(*im.mesh);
        // A scene file's own shape of an emissive material.
        if (!s.mesh && !s.instances && s.material >= 0 && scene.materials[static_cast<size_t>(s.material)].emits())
            lit = true;
    }
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

namespace {
// Calls f(mesh, copies) for every distinct mesh the imports hold: a mesh shared by entries or
// nodes once, with all its placements.
template <class F>
void for_each_held_mesh(const SceneDesc& scene, F&& f) {
    std::map<const MeshData*, uint64_t> copies;
    std::vector<const MeshData*> order;
    for (const ShapeDesc& s : scene.shapes) {
        if (s.mesh) f(*s.mesh, uint64_t(1));
        if (s.instances)
            for (const InstancedMesh& im : s.instances->meshes) {
                auto [it, fresh] = copies.try_emplace(im.mesh.get(), 0);
                if (fresh) order.push_back(im.mesh.get());
                it->second += im.placements.size();
            }
    }
    for (const MeshData* m : order) f(*m, copies[m]);
}
}  // namespace

uint64_t imported_mesh_bytes(const SceneDesc& scene) {
    uint64_t b = 0;
    for_each_held_mesh(scene, [&](const MeshData& m, uint64_t) { b += m.bytes(); });
    return b + imported_instances(scene) * sizeof(Affine);
}

uint64_t texture_bytes(const SceneDesc& scene) {
    uint64_t b = 0;
    for (const TextureDesc& t : scene.textures)
        if (t.image) b += t.image->bytes();
    return b;
}

uint64_t imported_bvh_bytes(const SceneDesc& scene) {
    uint64_t b = 0;
    for_each_held_mesh(scene, [&](const MeshData& m, uint64_t) {
        b += m.positions.size() * 12 + m.triangle_count() * (12 + kBvhBytesPerTriangle);
    });
    return b + imported_instances(scene) * kBytesPerInstance;
}

size_t emissive_triangles(const SceneDesc& scene) {
    size_t n = 0;
    for_each_held_mesh(scene, [&](const MeshData& m, uint64_t copies) {
        for (int32_t t : m.tri_material) n += copies * scene.materials[static_cast<size_t>(t)].emits();
    });
    return n;
}

size_t imported_triangles(const SceneDesc& scene) {
    size_t n = 0;
    for_each_held_mesh(scene, [&](const MeshData& m, uint64_t copies) { n += copies * m.triangle_count(); });
    return n;
}

size_t held_triangles(const SceneDesc& scene) {
    size_t n = 0;
    for_each_held_mesh(scene, [&](const MeshData& m, uint64_t) { n += m.triangle_count(); });
    return n;
}

size_t imported_instances(const SceneDesc& scene) {
    size_t n = 0;
    for (const ShapeDesc& s : scene.shapes)
        if (s.instances)
            for (const InstancedMesh& im : s.instances->meshes) n += im.placements.size();
    return n;
}

}  // namespace sl
