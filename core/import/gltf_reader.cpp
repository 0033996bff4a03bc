// glTF 2.0 (.gltf with .bin, or .glb) through tinygltf: the default scene's meshes with their
// node transforms, vertex normals and UVs, materials, KHR_lights_punctual lights and first
// camera. Every accessor is bounds-checked here (tinygltf does not), and images are kept
// encoded: they are decoded later, and only when a material that is drawn uses them.
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>

#include "config/limits.h"
#include "foundation/constants.h"
#include "foundation/errors.h"
#include "core/import/gltf_files.h"
#include "core/import/gltf_writer_base.h"
#include "core/import/gltf_node_expansion.h"
#include "core/import/imported_file.h"
#include "core/import/light_mapping.h"

namespace sl {
namespace fs = std::filesystem;

namespace {

constexpr uintmax_t kMaxModelBytes = uintmax_t(2) << 30;  // a .gltf/.glb, and each file it names

using Mat4 = std::array<double, 16>;  // column-major, as glTF stores it

Mat4 identity() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }

Mat4 mul(const Mat4& a, const Mat4& b) {
    Mat4 r{};
    for (int c = 0; c < 4; ++c)
        for (int rr = 0; rr < 4; ++rr) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += a[k * 4 + rr] * b[c * 4 + k];
            r[c * 4 + rr] = s;
        }
    return r;
}

Vec3 apply_point(const Mat4& m, Vec3 p) {
    return {static_cast<float>(m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12]),
            static_cast<float>(m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13]),
            static_cast<float>(m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14])};
}

Vec3 apply_vector(const Mat4& m, Vec3 v) {
    return {static_cast<float>(m[0] * v.x + m[4] * v.y + m[8] * v.z),
            static_cast<float>(m[1] * v.x + m[5] * v.y + m[9] * v.z),
            static_cast<float>(m[2] * v.x + m[6] * v.y + m[10] * v.z)};
}

double det3(const Mat4& m) {
    return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
           m[8] * (m[1] * m[6] - m[5] * m[2]);
}

// The inverse transpose of the upper 3x3 (for normals), as a Mat4 without translation.
Mat4 normal_matrix(const Mat4& m) {
    const double d = det3(m);
    Mat4 r = identity();
    if (d == 0) return r;
    // cofactor matrix / det = inverse transpose
    auto at = [&](int row, int col) { return m[col * 4 + row]; };
    double c[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            c[i][j] = at(i1, j1) * at(i2, j2) - at(i1, j2) * at(i2, j1);
        }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r[j * 4 + i] = c[i][j] / d;
    return r;
}

Mat4 local_matrix(const tinygltf::Node& n) {
    if (n.matrix.size() == 16) {
        Mat4 m;
        for (int i = 0; i < 16; ++i) m[i] = n.matrix[i];
        return m;
    }
    Mat4 t = identity(), r = identity(), s = identity();
    if (n.translation.size() == 3) { t[12] = n.translation[0]; t[13] = n.translation[1]; t[14] = n.translation[2]; }
    if (n.rotation.size() == 4) {
        double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
        double l = std::sqrt(x * x + y * y + z * z + w * w);
        if (l > 0) { x /= l; y /= l; z /= l; w /= l; }
        r = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0,
             2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0,
             2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0,
             0, 0, 0, 1};
    }
    if (n.scale.size() == 3) { s[0] = n.scale[0]; s[5] = n.scale[1]; s[10] = n.scale[2]; }
    return mul(t, mul(r, s));
}

// Keeps an image's encoded bytes (tinygltf would decode it with stb): decoding happens later,
// through OpenImageIO, for the images a drawn material uses.
// tinygltf hands over an image inside a bufferView without checking the view against its
// buffer (nor that its length fits an int): that is checked here, before a byte is copied.
bool keep_encoded(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                  const unsigned char* bytes, int size, void* user_data) {
    if (image->bufferView >= 0) {
        const auto* model = static_cast<const tinygltf::Model*>(user_data);
        const size_t v = static_cast<size_t>(image->bufferView);
        const bool ok = v < model->bufferViews.size() &&
                        static_cast<size_t>(model->bufferViews[v].buffer) < model->buffers.size() && [&] {
                            const tinygltf::BufferView& bv = model->bufferViews[v];
                            const size_t n = model->buffers[static_cast<size_t>(bv.buffer)].data.size();
                            return bv.byteOffset <= n && bv.byteLength <= n - bv.byteOffset &&
                                   bv.byteLength <= static_cast<size_t>(INT32_MAX);
                        }();
        if (!ok) {
            if (err)
                *err += "image " + std::to_string(index) + ": its bufferView " + std::to_string(image->bufferView) +
                        " reaches past the end of its buffer";
            return false;
        }
    }
    image->image.assign(bytes, bytes + std::max(size, 0));
    image->as_is = true;
    return true;
}

// The deepest nesting of arrays and objects the glTF JSON may have. tinygltf turns `extras` and
// extensions into values recursively: 100,000 nested brackets overflowed the stack inside the
// library, before any of this reader's checks. Real files nest under a dozen levels.
constexpr size_t kMaxJsonDepth = 64;
constexpr int kMaxNodeDepth = 256;

// Reads `length` bytes of JSON text from `f` and returns the offset (from the text's start) of
// the first bracket that opens level kMaxJsonDepth + 1, or -1. Brackets inside strings do not
// count. A linear scan in fixed memory: nothing is parsed.
int64_t too_deep_at(std::FILE* f, uint64_t length) {
    char chunk[1 << 16];
    size_t depth = 0;
    bool in_string = false, escaped = false;
    uint64_t at = 0;
    while (at < length) {
        const size_t want = static_cast<size_t>(std::min<uint64_t>(sizeof chunk, length - at));
        const size_t got = std::fread(chunk, 1, want, f);
        if (got == 0) break;
        for (size_t i = 0; i < got; ++i, ++at) {
            const char c = chunk[i];
            if (in_string) {
                if (escaped) escaped = false;
                else if (c == '\\') escaped = true;
                else if (c == '"') in_string = false;
            } else if (c == '"') {
                in_string = true;
            } else if (c == '[' || c == '{') {
                if (++depth > kMaxJsonDepth) return static_cast<int64_t>(at);
            } else if ((c == ']' || c == '}') && depth > 0) {
                --depth;
            }
        }
    }
    return -1;
}

class GltfReader {
public:
    GltfReader(const std::string& path, bool use_materials, LightUnits units)
        : path_(path), use_materials_(use_materials), units_(units), files_(path, kMaxModelBytes) {}

    ImportedFile read() {
        load();
        check_extensions();
        out_.writer_principled = principled_of_writer(model_.asset.generator);
        out_.files.push_back(path_);
        for (const auto& b : model_.buffers)
            if (!b.uri.empty() && b.uri.rfind("data:", 0) != 0)
                out_.files.push_back((fs::path(path_).parent_path() / b.uri).lexically_normal().string());
        // With a material given by the scene, the file's are neither read nor warned about.
        if (use_materials_)
            for (const auto& m : model_.materials) out_.materials.push_back(material(m));
        material_used_.assign(out_.materials.size(), false);
        int scene = model_.defaultScene >= 0 ? model_.defaultScene : 0;
        std::vector<int> roots;
        if (model_.scenes.empty()) {
            // No scene: every node without a parent is a root.
            std::vector<bool> child(model_.nodes.size(), false);
            for (const auto& n : model_.nodes)
                for (int c : n.children)
                    if (c >= 0 && static_cast<size_t>(c) < child.size()) child[static_cast<size_t>(c)] = true;
            for (size_t i = 0; i < model_.nodes.size(); ++i)
                if (!child[i]) roots.push_back(static_cast<int>(i));
        } else {
            if (static_cast<size_t>(scene) >= model_.scenes.size()) fail("the default scene " + std::to_string(scene) + " does not exist");
            roots = model_.scenes[static_cast<size_t>(scene)].nodes;
        }
        check_expansion(roots);
        mesh_uses_.assign(model_.meshes.size(), 0);
        for (int n : roots) count_uses(n);
        prototype_.assign(model_.meshes.size(), -1);
        for (int n : roots) visit(n, identity(), 0);
        // A mesh whose every triangle is degenerate places nothing.
        out_.instanced.erase(std::remove_if(out_.instanced.begin(), out_.instanced.end(),
                                            [](const ImportedInstances& i) { return i.mesh.indices.empty(); }),
                             out_.instanced.end());
        if (out_.mesh.indices.empty() && out_.instanced.empty() && out_.lights.empty())
            fail("the default scene has no triangles and no lights");
        auto shrink = [](MeshData& mesh) {
            mesh.positions.shrink_to_fit();
            mesh.normals.shrink_to_fit();
            mesh.uvs.shrink_to_fit();
            mesh.tangents.shrink_to_fit();
            mesh.indices.shrink_to_fit();
            mesh.tri_material.shrink_to_fit();
        };
        shrink(out_.mesh);
        for (ImportedInstances& i : out_.instanced) shrink(i.mesh);
        for (size_t i = 0; i < out_.materials.size(); ++i)
            if (material_used_[i])
                for (const std::string& w : material_warnings_[i]) out_.warnings.push_back(w);
        return std::move(out_);
    }

private:
    [[noreturn]] void fail(const std::string& why) const { throw InputError(path_ + ": " + why); }

    void warn(const std::string& why) { out_.warnings.push_back(path_ + ": " + why); }

    void load() {
        tinygltf::TinyGLTF loader;
        loader.SetImageLoader(keep_encoded, &model_);  // model_ is the model being loaded
        loader.SetFsCallbacks(files_.callbacks());
        std::string err, warn;
        std::error_code ec;
        if (!fs::is_regular_file(path_, ec)) fail("not found or not a regular file");
        auto size = fs::file_size(path_, ec);
        if (ec || size == 0) fail("is empty or unreadable");
        if (size > kMaxModelBytes) fail("is larger than 2 GiB");
        std::string ext = fs::path(path_).extension().string();
        for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        char magic[4] = {};
        {
            std::FILE* f = std::fopen(path_.c_str(), "rb");
            if (!f) fail("cannot be opened");
            size_t got = std::fread(magic, 1, 4, f);
            std::fclose(f);
            if (got < 4) fail("is too short to be glTF");
        }
        const bool binary = std::memcmp(magic, "glTF", 4) == 0;
        check_json_depth(binary, size);
        bool ok = false;
        try {
            const std::string& abs = files_.absolute_model_path();
            ok = binary ? loader.LoadBinaryFromFile(&model_, &err, &warn, abs)
                        : loader.LoadASCIIFromFile(&model_, &err, &warn, abs);
        } catch (const std::out_of_range&) {
            // tinygltf reads some parts with at(): a binary file whose first buffer claims 0 bytes
            // (found by fuzzing) throws instead of returning an error.
            fail("is malformed: an index or a length in it is out of range");
        } catch (const std::exception& e) {
            fail(std::string("cannot be parsed as glTF (") + e.what() + ")");
        }
        if (!ok && !files_.failure().empty()) fail(files_.failure());  // a file it names, in our words
        if (!ok) {
            std::string msg = err.empty() ? "cannot be parsed as glTF" : err;
            for (char& c : msg) if (c == '\n' || c == '\r') c = ' ';
            while (!msg.empty() && msg.back() == ' ') msg.pop_back();
            fail(msg.size() > 400 ? msg.substr(0, 400) + "..." : msg);
        }
        // tinygltf accepts a buffer shorter than its byteLength: that is a missing .bin in effect.
        for (size_t i = 0; i < model_.buffers.size(); ++i)
            if (model_.buffers[i].data.empty())
                fail("buffer " + std::to_string(i) + " (" + model_.buffers[i].uri + ") could not be loaded");
    }

    // The JSON text (a .gltf file, or a .glb's first chunk) must nest at most kMaxJsonDepth levels.
    void check_json_depth(bool binary, uintmax_t file_size) {
        std::FILE* f = std::fopen(path_.c_str(), "rb");
        if (!f) fail("cannot be opened");
        uint64_t length = file_size;
        bool ok = true;
        if (binary) {
            // 12-byte header, then the JSON chunk: its length, its type "JSON", its text.
            unsigned char head[20];
            ok = std::fread(head, 1, sizeof head, f) == sizeof head && std::memcmp(head + 16, "JSON", 4) == 0;
            uint32_t chunk = 0;
            std::memcpy(&chunk, head + 12, 4);  // little-endian, as the machine
            length = std::min<uint64_t>(chunk, file_size > 20 ? file_size - 20 : 0);
        }
        // A .glb whose first chunk is not JSON is tinygltf's to refuse.
        const int64_t at = ok ? too_deep_at(f, length) : -1;
        std::fclose(f);
        if (at >= 0)
            fail("its JSON is nested more than " + std::to_string(kMaxJsonDepth) + " levels deep (byte " +
                 std::to_string(at + (binary ? 20 : 0)) + ")");
    }

    void check_extensions() {
        static const std::set<std::string> supported = {
            "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_transmission",
            "KHR_materials_ior", "KHR_materials_specular"};
        for (const std::string& e : model_.extensionsRequired)
            if (!supported.count(e))
                fail("requires the extension " + e + ", which is not supported" +
                     (e == "KHR_draco_mesh_compression" || e == "EXT_meshopt_compression"
                          ? " (export without mesh compression)"
                          : ""));
        for (const std::string& e : model_.extensionsUsed)
            if (!supported.count(e)) warn("the extension " + e + " is ignored");
    }

    // --- materials ------------------------------------------------------------------------

    int texture(int index, bool srgb, const std::string& material, const char* role) {
        if (index < 0) return -1;
        if (static_cast<size_t>(index) >= model_.textures.size())
            fail("material '" + material + "': " + role + " texture " + std::to_string(index) + " does not exist");
        const tinygltf::Texture& t = model_.textures[static_cast<size_t>(index)];
        if (t.source < 0 || static_cast<size_t>(t.source) >= model_.images.size())
            fail("texture " + std::to_string(index) + " names no existing image");
        const tinygltf::Image& img = model_.images[static_cast<size_t>(t.source)];
        ImportedTexture it;
        it.desc.srgb = srgb;
        if (t.sampler >= 0 && static_cast<size_t>(t.sampler) < model_.samplers.size()) {
            const auto& s = model_.samplers[static_cast<size_t>(t.sampler)];
            auto wrap = [](int w) {
                return w == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE     ? TextureWrap::Clamp
                       : w == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? TextureWrap::MirroredRepeat
                                                                    : TextureWrap::Repeat;
            };
            it.desc.wrap_s = wrap(s.wrapS);
            it.desc.wrap_t = wrap(s.wrapT);
        }
        const bool external = !img.uri.empty() && img.uri.rfind("data:", 0) != 0;
        std::string name = external ? (fs::path(path_).parent_path() / img.uri).lexically_normal().string()
                                    : path_ + "#image" + std::to_string(t.source);
        if (img.image.empty() && external && !files_.failure_of(name).empty())
            fail("image " + std::to_string(t.source) + ": " + files_.failure_of(name));
        if (img.image.empty())
            fail("image " + std::to_string(t.source) + (external ? " (" + name + ")" : std::string()) +
                 " could not be loaded" + (external ? ": file missing or unreadable" : ""));
        it.desc.file = name;
        it.bytes = img.image;
        std::string mime = img.mimeType;
        it.format = mime == "image/jpeg" ? "jpg" : mime == "image/png" ? "png" : "";
        if (it.format.empty()) {
            std::string ext = fs::path(external ? img.uri : std::string()).extension().string();
            it.format = ext.size() > 1 ? ext.substr(1) : "png";
        }
        if (external) out_.files.push_back(name);
        const int id = static_cast<int>(out_.textures.size());
        out_.textures.push_back(std::move(it));
        return id;
    }

    static double ext_number(const tinygltf::ExtensionMap& ext, const char* name, const char* key, double dflt,
                             bool* present = nullptr) {
        auto it = ext.find(name);
        if (it == ext.end()) return dflt;
        if (present) *present = true;
        if (!it->second.Has(key)) return dflt;
        const tinygltf::Value& v = it->second.Get(key);
        return v.IsNumber() ? v.GetNumberAsDouble() : dflt;
    }

    static Vec3 ext_color(const tinygltf::ExtensionMap& ext, const char* name, const char* key, Vec3 dflt) {
        auto it = ext.find(name);
        if (it == ext.end() || !it->second.Has(key)) return dflt;
        const tinygltf::Value& v = it->second.Get(key);
        if (!v.IsArray() || v.ArrayLen() < 3) return dflt;
        Vec3 c = dflt;
        for (int i = 0; i < 3; ++i)
            if (v.Get(i).IsNumber()) c[i] = static_cast<float>(std::clamp(v.Get(i).GetNumberAsDouble(), 0.0, 1e3));
        return c;
    }

    MaterialDesc material(const tinygltf::Material& gm) {
        MaterialDesc m;
        const std::string name = gm.name.empty() ? "material " + std::to_string(out_.materials.size()) : gm.name;
        m.name = name;
        std::vector<std::string> notes;
        const auto& pbr = gm.pbrMetallicRoughness;
        Vec3 base{1, 1, 1};
        if (pbr.baseColorFactor.size() >= 3)
            base = {static_cast<float>(pbr.baseColorFactor[0]), static_cast<float>(pbr.baseColorFactor[1]),
                    static_cast<float>(pbr.baseColorFactor[2])};
        base = vmin(vmax(base, Vec3(0)), Vec3(1));
        const double metallic = pbr.metallicFactor, roughness = pbr.roughnessFactor;
        bool has_transmission = false, has_strength = false;
        const double transmission =
            ext_number(gm.extensions, "KHR_materials_transmission", "transmissionFactor", 0, &has_transmission);
        const double ior = ext_number(gm.extensions, "KHR_materials_ior", "ior", 1.5);
        const double strength =
            ext_number(gm.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1, &has_strength);
        if (gm.emissiveFactor.size() == 3)
            m.emission = Vec3(static_cast<float>(gm.emissiveFactor[0]), static_cast<float>(gm.emissiveFactor[1]),
                              static_cast<float>(gm.emissiveFactor[2])) *
                         static_cast<float>(strength);
        if (!is_finite(m.emission) || m.emission.x < 0 || m.emission.y < 0 || m.emission.z < 0)
            fail("material '" + name + "': the emission is negative or not finite");
        // As a scene file's radiance: beyond 1e30 the light's power overflows single precision.
        if (max_component(m.emission) > static_cast<float>(limits::kMaxEmission))
            fail("material '" + name + "': the emission (emissiveFactor x emissiveStrength) is larger than 1e30, "
                 "the largest radiance accepted");
        m.double_sided = gm.doubleSided;
        // glTF's metallic-roughness material as it is meant (core/bsdf/bsdf.h evaluates it).
        m.type = MaterialType::MetallicRoughness;
        m.albedo = base;
        m.metallic = static_cast<float>(std::clamp(metallic, 0.0, 1.0));
        m.roughness = static_cast<float>(std::clamp(roughness, 0.0, 1.0));
        m.transmission = static_cast<float>(std::clamp(transmission, 0.0, 1.0));
        m.ior = static_cast<float>(ior >= 1 && ior <= 100 ? ior : 1.5);
        if (ior != 0 && (ior < 1 || ior > 100)) notes.push_back("an ior outside [1, 100] is read as 1.5");
        if (ior == 0) m.ior = 1.5f;  // KHR_materials_ior: 0 means the old specular-glossiness 'no Fresnel'
        if (m.transmission > 0 && m.ior == 1) m.ior = 1.5f;
        // KHR_materials_specular: specularFactor and specularColorFactor scale the dielectric F0.
        m.specular = static_cast<float>(std::clamp(ext_number(gm.extensions, "KHR_materials_specular", "specularFactor", 1), 0.0, 1.0));
        m.specular_color = ext_color(gm.extensions, "KHR_materials_specular", "specularColorFactor", Vec3(1));
        m.albedo_texture = texture(pbr.baseColorTexture.index, true, name, "base colour");
        // Linear data: G scales the roughness, B the metallic factor (core/glossy_path.h).
        m.metallic_roughness_texture = texture(pbr.metallicRoughnessTexture.index, false, name, "metallic-roughness");
        // A tangent-space normal map, linear (core/surface_material.h).
        m.normal_texture = texture(gm.normalTexture.index, false, name, "normal");
        m.normal_scale = std::isfinite(gm.normalTexture.scale) ? static_cast<float>(gm.normalTexture.scale) : 1.0f;
        if ((pbr.baseColorTexture.index >= 0 && pbr.baseColorTexture.texCoord != 0) ||
            (pbr.metallicRoughnessTexture.index >= 0 && pbr.metallicRoughnessTexture.texCoord != 0) ||
            (gm.normalTexture.index >= 0 && gm.normalTexture.texCoord != 0))
            notes.push_back("only TEXCOORD_0 is used");
        if (m.emits()) m.emission_texture = texture(gm.emissiveTexture.index, true, name, "emissive");
        if (gm.alphaMode == "BLEND" || gm.alphaMode == "MASK")
            notes.push_back("alpha " + gm.alphaMode + " is ignored (the surface is opaque)");
        std::vector<std::string> lines;
        if (!notes.empty()) {
            std::string all;
            for (const auto& n : notes) all += (all.empty() ? "" : "; ") + n;
            lines.push_back(path_ + ": material '" + name + "': " + all);
        }
        material_warnings_.push_back(lines);
        return m;
    }

    // --- accessors ------------------------------------------------------------------------

    // The bytes of accessor `index`, checked against its view and buffer; `comps` components.
    struct View {
        const unsigned char* data;
        size_t stride, count, elem;
        int component_type;
        bool normalized;
    };

    View accessor(int index, int type, const char* what, const std::string& where) {
        if (index < 0 || static_cast<size_t>(index) >= model_.accessors.size())
            fail(where + ": " + what + " accessor " + std::to_string(index) + " does not exist");
        const tinygltf::Accessor& a = model_.accessors[static_cast<size_t>(index)];
        const std::string ac = where + ": " + what + " accessor " + std::to_string(index);
        if (a.type != type) fail(ac + " has the wrong type");
        if (a.sparse.isSparse) fail(ac + " is sparse, which is not supported");
        if (a.bufferView < 0 || static_cast<size_t>(a.bufferView) >= model_.bufferViews.size())
            fail(ac + " has no valid bufferView");
        const tinygltf::BufferView& bv = model_.bufferViews[static_cast<size_t>(a.bufferView)];
        const std::string bvn = "bufferView " + std::to_string(a.bufferView);
        if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= model_.buffers.size())
            fail(ac + ": its " + bvn + " names no existing buffer");
        const auto& buf = model_.buffers[static_cast<size_t>(bv.buffer)].data;
        const int csize = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
        const int ncomp = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
        if (csize <= 0 || ncomp <= 0) fail(ac + " has an unknown component type");
        // Every size, offset, stride and count comes from the file: each sum and product is
        // checked for overflow, and the view against its buffer, before a byte is read.
        const size_t elem = static_cast<size_t>(csize) * static_cast<size_t>(ncomp);
        if (bv.byteOffset > buf.size() || bv.byteLength > buf.size() - bv.byteOffset)
            fail(bvn + " (of " + ac + ") reaches past the end of buffer " + std::to_string(bv.buffer) + " (offset " +
                 std::to_string(bv.byteOffset) + ", length " + std::to_string(bv.byteLength) + ", buffer " +
                 std::to_string(buf.size()) + " bytes)");
        if (bv.byteStride != 0 && bv.byteStride < elem)
            fail(bvn + " (of " + ac + "): byteStride " + std::to_string(bv.byteStride) +
                 " is smaller than the accessor's element of " + std::to_string(elem) + " bytes");
        const size_t stride = bv.byteStride > 0 ? bv.byteStride : elem;
        const size_t count = a.count;
        size_t need = 0;  // stride * (count - 1) + elem
        if (count > 0 && (__builtin_mul_overflow(stride, count - 1, &need) || __builtin_add_overflow(need, elem, &need)))
            fail(ac + ": " + std::to_string(count) + " elements of stride " + std::to_string(stride) +
                 " overflow any size");
        if (a.byteOffset > bv.byteLength || need > bv.byteLength - a.byteOffset)
            fail(ac + " reaches past the end of its " + bvn + " (" + std::to_string(count) + " elements from offset " +
                 std::to_string(a.byteOffset) + ", " + std::to_string(bv.byteLength) + " bytes in the view)");
        const size_t begin = bv.byteOffset + a.byteOffset;  // <= buf.size(): checked above
        return {buf.data() + begin, stride, count, elem, a.componentType, a.normalized};
    }

    float component(const View& v, size_t i, int k) const {
        const unsigned char* p = v.data + v.stride * i;
        switch (v.component_type) {
            case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p + 4 * k, 4); return f; }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[k] / 255.0f;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t s; std::memcpy(&s, p + 2 * k, 2); return s / 65535.0f; }
            default: return 0;
        }
    }

    // The graph's size once every path is placed, bounded before anything is placed.
    void check_expansion(const std::vector<int>& roots) const {
        NodeExpansion e;
        const std::string why = count_expansion(model_, roots, kMaxNodeDepth, e);
        if (!why.empty()) fail(why);
        auto over = [&](uint64_t n, uint64_t limit, const char* what) {
            if (n > limit)
                fail("its node graph places " + (n >= (uint64_t(1) << 62) ? std::string("more than 2^62") : std::to_string(n)) +
                     " " + what + " (nodes reached by several paths are placed once per path); at most " +
                     std::to_string(limit) + " are rendered");
        };
        over(e.visits, limits::kMaxNodeVisits, "nodes");
        over(e.triangles, limits::kMaxImportedTriangles, "triangles");
        over(e.vertices, limits::kMaxImportedVertices, "vertices");
    }

    // How many times each mesh is placed (the graph is bounded and acyclic: check_expansion).
    void count_uses(int node) {
        const tinygltf::Node& n = model_.nodes[static_cast<size_t>(node)];
        if (n.mesh >= 0 && static_cast<size_t>(n.mesh) < mesh_uses_.size()) ++mesh_uses_[static_cast<size_t>(n.mesh)];
        for (int c : n.children) count_uses(c);
    }

    void visit(int node, const Mat4& parent, int depth) {
        if (node < 0 || static_cast<size_t>(node) >= model_.nodes.size()) fail("node " + std::to_string(node) + " does not exist");
        if (depth > kMaxNodeDepth) fail("the node hierarchy is deeper than " + std::to_string(kMaxNodeDepth) + " levels");
        const tinygltf::Node& n = model_.nodes[static_cast<size_t>(node)];
        check_transform(n, node);
        const Mat4 m = mul(parent, local_matrix(n));
        if (n.mesh >= 0) {
            if (static_cast<size_t>(n.mesh) >= model_.meshes.size()) fail("node " + std::to_string(node) + ": mesh " + std::to_string(n.mesh) + " does not exist");
            if (mesh_uses_[static_cast<size_t>(n.mesh)] > 1) place_instance(n.mesh, m, node);
            else add_mesh(model_.meshes[static_cast<size_t>(n.mesh)], n.mesh, m, out_.mesh);
        }
        if (n.camera >= 0 && !out_.camera) camera(n.camera, m);
        auto lit = n.extensions.find("KHR_lights_punctual");
        if (lit != n.extensions.end() && lit->second.Has("light")) {
            int li = lit->second.Get("light").GetNumberAsInt();
            if (li < 0 || static_cast<size_t>(li) >= model_.lights.size()) fail("node " + std::to_string(node) + ": light " + std::to_string(li) + " does not exist");
            light(model_.lights[static_cast<size_t>(li)], li, m);
        }
        for (int c : n.children) visit(c, m, depth + 1);
    }

    // A node's numbers: finite, and a rotation that is a rotation (a zero quaternion is none).
    void check_transform(const tinygltf::Node& n, int node) const {
        auto finite = [&](const std::vector<double>& v, const char* what) {
            for (double x : v)
                if (!std::isfinite(x) || std::fabs(x) > limits::kMaxLength)
                    fail("node " + std::to_string(node) + ": its " + what + " holds a number that is not finite or beyond 1e9");
        };
        finite(n.matrix, "matrix");
        finite(n.translation, "translation");
        finite(n.rotation, "rotation");
        finite(n.scale, "scale");
        if (n.rotation.size() == 4) {
            double l2 = 0;
            for (double x : n.rotation) l2 += x * x;
            if (!(l2 > 1e-12)) fail("node " + std::to_string(node) + ": its rotation is a zero quaternion (no rotation at all)");
        }
    }

    // A mesh placed more than once: read once in its own space (nested nodes' transforms are
    // multiplied into one placement: instances are one level deep), placed by `m`.
    void place_instance(int mesh_index, const Mat4& m, int node) {
        int& proto = prototype_[static_cast<size_t>(mesh_index)];
        if (proto < 0) {
            ImportedInstances fresh;
            add_mesh(model_.meshes[static_cast<size_t>(mesh_index)], mesh_index, identity(), fresh.mesh);
            proto = static_cast<int>(out_.instanced.size());
            out_.instanced.push_back(std::move(fresh));
        }
        ImportedInstances& in = out_.instanced[static_cast<size_t>(proto)];
        Affine a;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) a.m[4 * r + c] = static_cast<float>(m[c * 4 + r]);
        // As a placed vertex: a huge vertex times a node's scale can overflow (the box's
        // corners hold the largest coordinates any vertex reaches).
        Vec3 lo(1e30f), hi(-1e30f);
        for (Vec3 p : in.mesh.positions) { lo = vmin(lo, p); hi = vmax(hi, p); }
        for (int k = 0; k < 8 && !in.mesh.positions.empty(); ++k)
            if (!is_finite(a.point({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z})))
                fail("node " + std::to_string(node) + ": mesh " + std::to_string(mesh_index) +
                     ": a POSITION is not finite once placed by its nodes");
        in.placements.push_back(a);
    }

    void add_mesh(const tinygltf::Mesh& mesh, int mesh_index, const Mat4& m, MeshData& out) {
        const Mat4 nm = normal_matrix(m);
        const bool flip = det3(m) < 0;
        std::map<std::tuple<int, int, int, int>, uint32_t> placed;
        for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
            const tinygltf::Primitive& p = mesh.primitives[pi];
            const std::string where = "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(pi);
            if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
                p.mode != TINYGLTF_MODE_TRIANGLE_FAN && p.mode != -1)
                fail(where + ": mode " + std::to_string(p.mode) + " (points or lines) is not supported; only triangles are");
            for (const auto& e : p.extensions)
                fail(where + ": uses the extension " + e.first + ", which is not supported");
            auto pos_it = p.attributes.find("POSITION");
            if (pos_it == p.attributes.end()) fail(where + ": has no POSITION");
            View pv = accessor(pos_it->second, TINYGLTF_TYPE_VEC3, "POSITION", where);
            if (pv.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT) fail(where + ": POSITION must be float");
            std::optional<View> nv, tv, gv;
            if (auto it = p.attributes.find("NORMAL"); it != p.attributes.end()) {
                nv = accessor(it->second, TINYGLTF_TYPE_VEC3, "NORMAL", where);
                if (nv->count != pv.count || nv->component_type != TINYGLTF_COMPONENT_TYPE_FLOAT)
                    fail(where + ": NORMAL must be float and as long as POSITION");
            }
            if (auto it = p.attributes.find("TEXCOORD_0"); it != p.attributes.end()) {
                tv = accessor(it->second, TINYGLTF_TYPE_VEC2, "TEXCOORD_0", where);
                if (tv->count != pv.count) fail(where + ": TEXCOORD_0 must be as long as POSITION");
            }
            if (p.material >= static_cast<int>(model_.materials.size()))
                fail(where + ": material " + std::to_string(p.material) + " does not exist");
            // Tangents for normal maps (MikkTSpace in glTF; core/scene_geometry.cpp otherwise),
            // read only for a primitive whose own material draws one.
            const bool normal_mapped = use_materials_ && p.material >= 0 &&
                                       model_.materials[static_cast<size_t>(p.material)].normalTexture.index >= 0;
            if (auto it = p.attributes.find("TANGENT"); it != p.attributes.end() && tv && normal_mapped) {
                gv = accessor(it->second, TINYGLTF_TYPE_VEC4, "TANGENT", where);
                if (gv->count != pv.count || gv->component_type != TINYGLTF_COMPONENT_TYPE_FLOAT)
                    fail(where + ": TANGENT must be float and as long as POSITION");
            }
            int material = use_materials_ ? p.material : -1;
            if (material >= static_cast<int>(out_.materials.size())) fail(where + ": material " + std::to_string(material) + " does not exist");
            if (material < 0) {
                if (default_material_ < 0) {
                    MaterialDesc d;
                    d.name = "default";
                    default_material_ = static_cast<int>(out_.materials.size());
                    out_.materials.push_back(d);
                    material_used_.push_back(false);
                    material_warnings_.emplace_back();
                }
                material = default_material_;
            }
            material_used_[static_cast<size_t>(material)] = true;
            // Primitives of one mesh often share their vertex accessors: place those once.
            const auto key = std::make_tuple(pos_it->second, nv ? p.attributes.at("NORMAL") : -1,
                                             tv ? p.attributes.at("TEXCOORD_0") : -1, gv ? p.attributes.at("TANGENT") : -1);
            auto [shared, fresh] = placed.try_emplace(key, static_cast<uint32_t>(out.positions.size()));
            const uint32_t base = shared->second;
            if (fresh) add_vertices(pv, nv, tv, gv, m, nm, flip, where, out);
            add_triangles(p, pv.count, base, flip, material, where, out);
        }
    }

    void add_vertices(const View& pv, const std::optional<View>& nv, const std::optional<View>& tv,
                      const std::optional<View>& gv, const Mat4& m, const Mat4& nm, bool flip, const std::string& where,
                      MeshData& out) {
        {
            const uint32_t base = static_cast<uint32_t>(out.positions.size());
            const bool any_normals_before = !out.normals.empty() || base == 0;
            for (size_t i = 0; i < pv.count; ++i) {
                Vec3 v{component(pv, i, 0), component(pv, i, 1), component(pv, i, 2)};
                if (!is_finite(v)) fail(where + ": POSITION " + std::to_string(i) + " is not finite");
                const Vec3 placed = apply_point(m, v);  // a huge vertex times a node's scale can overflow
                if (!is_finite(placed)) fail(where + ": POSITION " + std::to_string(i) + " is not finite once placed by its nodes");
                out.positions.push_back(placed);
            }
            // Normals: this primitive's, or (if it has none while others do) zero (= flat).
            if (nv) {
                if (!any_normals_before) out.normals.resize(base, Vec3(0));
                for (size_t i = 0; i < pv.count; ++i) {
                    Vec3 n{component(*nv, i, 0), component(*nv, i, 1), component(*nv, i, 2)};
                    if (!is_finite(n)) fail(where + ": NORMAL " + std::to_string(i) + " is not finite");
                    Vec3 w = apply_vector(nm, n);
                    float l = length(w);
                    out.normals.push_back(l > 0 ? w / l : Vec3(0));
                }
            } else if (!out.normals.empty()) {
                out.normals.resize(out.positions.size(), Vec3(0));
            }
            if (tv) {
                if (out.uvs.size() < 2 * base) out.uvs.resize(2 * base, 0.0f);
                for (size_t i = 0; i < pv.count; ++i) {
                    float u = component(*tv, i, 0), v = component(*tv, i, 1);
                    if (!std::isfinite(u) || !std::isfinite(v)) fail(where + ": TEXCOORD_0 " + std::to_string(i) + " is not finite");
                    out.uvs.push_back(u);
                    out.uvs.push_back(v);
                }
            } else if (!out.uvs.empty()) {
                out.uvs.resize(2 * out.positions.size(), 0.0f);
            }
            // Tangents: placed as directions (a mirroring node flips the handedness w); zero
            // where a primitive has none (its frames then come from its UVs).
            if (gv) {
                if (out.tangents.size() < 4 * base) out.tangents.resize(4 * base, 0.0f);
                for (size_t i = 0; i < pv.count; ++i) {
                    Vec3 t{component(*gv, i, 0), component(*gv, i, 1), component(*gv, i, 2)};
                    const float w = component(*gv, i, 3);
                    if (!is_finite(t) || !std::isfinite(w)) fail(where + ": TANGENT " + std::to_string(i) + " is not finite");
                    t = apply_vector(m, t);
                    const float l = length(t);
                    out.tangents.insert(out.tangents.end(), {l > 0 ? t.x / l : 0, l > 0 ? t.y / l : 0, l > 0 ? t.z / l : 0,
                                                             (w < 0) != flip ? -1.0f : 1.0f});
                }
            } else if (!out.tangents.empty()) {
                out.tangents.resize(4 * out.positions.size(), 0.0f);
            }
        }
    }

    void add_triangles(const tinygltf::Primitive& p, size_t vertex_count, uint32_t base, bool flip, int material,
                       const std::string& where, MeshData& out) {
        const View pv{nullptr, 0, vertex_count, 0, 0, false};
        {
            // Indices (or 0..n-1), as a triangle list.
            std::vector<uint32_t> idx;
            if (p.indices >= 0) {
                View iv = accessor(p.indices, TINYGLTF_TYPE_SCALAR, "indices", where);
                idx.reserve(iv.count);
                for (size_t i = 0; i < iv.count; ++i) {
                    const unsigned char* q = iv.data + iv.stride * i;
                    uint32_t k;
                    switch (iv.component_type) {
                        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: k = q[0]; break;
                        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t s; std::memcpy(&s, q, 2); k = s; break; }
                        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(&k, q, 4); break;
                        default: fail(where + ": indices must be unsigned integers");
                    }
                    if (k >= pv.count) fail(where + ": index " + std::to_string(k) + " is out of range (" + std::to_string(pv.count) + " vertices)");
                    idx.push_back(k);
                }
            } else {
                for (size_t i = 0; i < pv.count; ++i) idx.push_back(static_cast<uint32_t>(i));
            }
            std::vector<uint32_t> tris;
            if (p.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                for (size_t i = 0; i + 2 < idx.size(); ++i)
                    if (i % 2 == 0) tris.insert(tris.end(), {idx[i], idx[i + 1], idx[i + 2]});
                    else tris.insert(tris.end(), {idx[i + 1], idx[i], idx[i + 2]});
            } else if (p.mode == TINYGLTF_MODE_TRIANGLE_FAN) {
                for (size_t i = 1; i + 1 < idx.size(); ++i) tris.insert(tris.end(), {idx[0], idx[i], idx[i + 1]});
            } else {
                if (idx.size() % 3 != 0) fail(where + ": the index count " + std::to_string(idx.size()) + " is not a multiple of 3");
                tris = std::move(idx);
            }
            for (size_t t = 0; t + 2 < tris.size(); t += 3) {
                uint32_t a = base + tris[t], b = base + tris[t + (flip ? 2 : 1)], c = base + tris[t + (flip ? 1 : 2)];
                Vec3 e = cross(out.positions[b] - out.positions[a], out.positions[c] - out.positions[a]);
                if (!(length(e) > 0)) continue;  // degenerate: no area, no light
                out.indices.insert(out.indices.end(), {a, b, c});
                out.tri_material.push_back(material);
            }
        }
    }

    void camera(int index, const Mat4& m) {
        if (static_cast<size_t>(index) >= model_.cameras.size()) fail("camera " + std::to_string(index) + " does not exist");
        const tinygltf::Camera& c = model_.cameras[static_cast<size_t>(index)];
        CameraDesc cam;
        cam.position = apply_point(m, Vec3(0));
        Vec3 fwd = apply_vector(m, Vec3(0, 0, -1)), up = apply_vector(m, Vec3(0, 1, 0));
        if (!(length(fwd) > 0) || !(length(up) > 0)) return;
        cam.look_at = cam.position + normalize(fwd);
        cam.up = normalize(up);
        if (c.type == "perspective") {
            const std::string which = "camera " + std::to_string(index);
            const double yfov = c.perspective.yfov * 180.0 / kPiDouble;
            if (!(yfov > 0.01 && yfov < 179))
                fail(which + ": yfov " + std::to_string(c.perspective.yfov) + " is not an angle between 0 and pi radians");
            cam.vfov_deg = static_cast<float>(yfov);
            const double aspect = c.perspective.aspectRatio;
            if (aspect != 0) {  // (0: absent, the spec's "use the viewport's")
                // 256 pixels high; the width must stay an image side we can render.
                if (!std::isfinite(aspect) || !(aspect * 256 >= 1) || !(aspect * 256 <= limits::kMaxImageSide))
                    fail(which + ": aspectRatio " + std::to_string(aspect) + " is not between 1/256 and " +
                         std::to_string(limits::kMaxImageSide / 256) + " (256 pixels high)");
                cam.height = 256;
                cam.width = static_cast<int>(std::lround(256 * aspect));
            }
        } else {
            warn("camera " + std::to_string(index) + " is orthographic: drawn as a 40 degree perspective camera");
        }
        out_.camera = cam;
    }

    void light(const tinygltf::Light& l, int index, const Mat4& m) {
        Vec3 color{1, 1, 1};
        if (l.color.size() == 3) color = {static_cast<float>(l.color[0]), static_cast<float>(l.color[1]), static_cast<float>(l.color[2])};
        PunctualLight p;
        p.name = l.name;
        p.type = l.type;
        p.color = color;
        p.intensity = l.intensity;
        p.range = l.range;
        p.inner_cone = l.spot.innerConeAngle;
        p.outer_cone = l.spot.outerConeAngle;
        p.position = apply_point(m, Vec3(0));
        p.direction = apply_vector(m, Vec3(0, 0, -1));
        std::string warning;
        if (std::optional<LightDesc> d = map_punctual_light(p, units_, warning)) {
            // The scene file's bound on a light's power (W) and a sun's irradiance (W/m^2).
            const Vec3 e = d->type == LightType::Sun ? d->irradiance : d->power;
            if (!is_finite(e) || max_component(e) > static_cast<float>(limits::kMaxEmission))
                fail("light " + std::to_string(index) + (l.name.empty() ? "" : " ('" + l.name + "')") +
                     ": its " + (d->type == LightType::Sun ? "irradiance" : "power") +
                     " (colour x intensity) is larger than 1e30, the largest accepted");
            out_.lights.push_back(*d);
        }
        if (!warning.empty()) warn(warning);
    }

    std::string path_;
    bool use_materials_;
    LightUnits units_;
    GltfFiles files_;  // the files the model names: from its folder only, through the guard
    tinygltf::Model model_;
    ImportedFile out_;
    std::vector<bool> material_used_;
    std::vector<std::vector<std::string>> material_warnings_;
    int default_material_ = -1;
    std::vector<uint64_t> mesh_uses_;  // per mesh: its placements in the default scene
    std::vector<int> prototype_;       // per mesh placed more than once: its out_.instanced entry
};

}  // namespace

ImportedFile read_gltf(const std::string& path, bool read_materials, LightUnits units) {
    return GltfReader(path, read_materials, units).read();
}

}  // namespace sl
