// OBJ with its MTL materials, read strictly: every number must be a whole finite number token
// (tinyobjloader reads "nan", "abc" or "0x10" as 0 and wraps huge indices), and every error
// names the file and line.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string_view>
#include <unordered_map>

#include "config/limits.h"
#include "config/input_file.h"
#include "foundation/errors.h"
#include "foundation/xxh64.h"
#include "core/import/imported_file.h"

namespace sl {
namespace fs = std::filesystem;

namespace {

constexpr uintmax_t kMaxTextBytes = uintmax_t(1) << 30;

// Through the regular-file and size guard: a FIFO, a device or a directory is named as what it
// is (not "missing"), and nothing is opened before the checks.
std::string read_text(const std::string& path, const std::string& what) {
    return read_input_file(path, kMaxTextBytes, path, what);
}

// Splits a line into whitespace-separated tokens (views into the line).
std::vector<std::string_view> tokens_of(std::string_view line) {
    std::vector<std::string_view> t;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        size_t j = i;
        while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
        if (j > i) t.push_back(line.substr(i, j - i));
        i = j;
    }
    return t;
}

// Everything after the keyword, trimmed: a file or material name may hold spaces.
std::string rest_of(std::string_view line, std::string_view keyword) {
    size_t i = line.find(keyword) + keyword.size();
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    size_t j = line.size();
    while (j > i && (line[j - 1] == ' ' || line[j - 1] == '\t' || line[j - 1] == '\r')) --j;
    return std::string(line.substr(i, j - i));
}

struct LineReader {
    const std::string& file;
    size_t line_no = 0;
    // A material library may be any file `mtllib` names: its errors quote
    // none of its text, only the file and the line.
    bool quote = true;

    [[noreturn]] void fail(const std::string& why) const {
        throw InputError(file + ":" + std::to_string(line_no) + ": " + why);
    }
    std::string q(std::string_view tok) const { return quote ? "'" + std::string(tok) + "'" : std::string("a value"); }

    float number(std::string_view tok) const {
        float v = 0;
        const char* b = tok.data();
        const char* e = b + tok.size();
        if (!tok.empty() && *b == '+') ++b;
        auto r = std::from_chars(b, e, v, std::chars_format::general);
        if (r.ec == std::errc::result_out_of_range) fail("number " + q(tok) + " is out of range");
        if (r.ec != std::errc() || r.ptr != e) fail(q(tok) + " is not a number");
        if (!std::isfinite(v)) fail("number " + q(tok) + " is not finite");
        return v;
    }

    Vec3 triple(const std::vector<std::string_view>& t, size_t need) const {
        if (t.size() < 1 + need) fail("'" + std::string(t[0]) + "' needs " + std::to_string(need) + " numbers");
        Vec3 v;
        float c[3] = {0, 0, 0};
        for (size_t k = 0; k < need && k < 3; ++k) c[k] = number(t[1 + k]);
        for (size_t k = 1 + need; k < t.size(); ++k) number(t[k]);  // extra values must be numbers too
        v = {c[0], c[1], c[2]};
        return v;
    }

    // An OBJ index (1-based, or negative: relative to the end) into a list of `count` items.
    int64_t index(std::string_view tok, size_t count, const char* what) const {
        int64_t i = 0;
        auto r = std::from_chars(tok.data(), tok.data() + tok.size(), i);
        if (r.ec != std::errc() || r.ptr != tok.data() + tok.size())
            fail(std::string(what) + " index '" + std::string(tok) + "' is not an integer");
        int64_t resolved = i < 0 ? static_cast<int64_t>(count) + i : i - 1;
        if (i == 0 || resolved < 0 || resolved >= static_cast<int64_t>(count))
            fail(std::string(what) + " index " + std::string(tok) + " is out of range (" + std::to_string(count) +
                 " defined so far)");
        return resolved;
    }
};

// The materials of every library an OBJ names, in the order read; a name defined again in a
// later library means the later definition.
struct MtlResult {
    std::map<std::string, int> index;
    std::vector<MaterialDesc> materials;
    std::set<std::string> libraries;  // read already (a library named twice is read once)
};

// A texture statement's file: the last token (options such as -s or -bm come before it).
std::string texture_path(const LineReader& lr, const std::vector<std::string_view>& t, const fs::path& dir,
                         std::string& note) {
    if (t.size() < 2) lr.fail("'" + std::string(t[0]) + "' names no file");
    if (t.size() > 2) note = "options of " + std::string(t[0]) + " are ignored (the texture is used as is)";
    fs::path p(std::string(t.back()));
    if (p.is_relative()) p = dir / p;
    p = p.lexically_normal();
    std::error_code ec;
    if (!fs::exists(p, ec)) lr.fail(std::string(t[0]) + " names a missing texture file: " + p.string());
    try {
        check_input_file(p.string(), limits::kMaxTextureFileBytes, p.string(), "texture");
    } catch (const InputError& e) {
        lr.fail(std::string(t[0]) + " names " + e.what());
    }
    return p.string();
}

int add_texture(ImportedFile& out, const std::string& path, bool srgb) {
    for (size_t i = 0; i < out.textures.size(); ++i)
        if (out.textures[i].desc.file == path && out.textures[i].desc.srgb == srgb) return static_cast<int>(i);
    out.files.push_back(path);
    ImportedTexture t;
    t.desc.file = path;
    t.desc.srgb = srgb;
    out.textures.push_back(std::move(t));
    return static_cast<int>(out.textures.size() - 1);
}

void read_mtl(const std::string& path, ImportedFile& out, MtlResult& mtl) {
    if (!mtl.libraries.insert(path).second) return;
    const std::string text = read_text(path, "material library (.mtl)");
    out.files.push_back(path);
    const fs::path dir = fs::path(path).parent_path();
    LineReader lr{path};
    lr.quote = false;
    MaterialDesc* cur = nullptr;
    // This library's materials are mtl.materials[first..]; extra and notes are this call's.
    const size_t first = mtl.materials.size();
    struct Extra { Vec3 ks{0}; int illum = -1; float d = 1; float ns = -1; bool ke_set = false; size_t ke_line = 0; };
    std::vector<Extra> extra;
    // What each material loses, gathered into one warning line per material at the end.
    std::vector<std::vector<std::string>> notes;
    size_t cur_index = 0;
    auto warn_once = [&](const std::string&, const std::string& why) {
        if (!cur) return;
        auto& n = notes[cur_index];
        if (std::find(n.begin(), n.end(), why) == n.end()) n.push_back(why);
    };
    size_t pos = 0;
    while (pos < text.size()) {
        size_t end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        std::string_view line(text.data() + pos, end - pos);
        pos = end + 1;
        ++lr.line_no;
        auto t = tokens_of(line);
        if (t.empty() || t[0][0] == '#') continue;
        const std::string_view k = t[0];
        if (k == "newmtl") {
            std::string name = rest_of(line, "newmtl");
            if (name.empty()) lr.fail("newmtl names no material");
            MaterialDesc m;
            m.name = name;
            mtl.index[name] = static_cast<int>(mtl.materials.size());
            mtl.materials.push_back(m);
            extra.emplace_back();
            notes.emplace_back();
            cur = &mtl.materials.back();
            cur_index = extra.size() - 1;
            continue;
        }
        if (!cur) lr.fail("a statement before any newmtl: not a material library");
        Extra& x = extra.back();
        if (k == "Kd") {
            cur->albedo = lr.triple(t, 3);
            if (t.size() == 2) cur->albedo = Vec3(cur->albedo.x);
        } else if (k == "Ke") {
            cur->emission = lr.triple(t, t.size() == 2 ? 1 : 3);
            if (t.size() == 2) cur->emission = Vec3(cur->emission.x);
            x.ke_set = true;
            x.ke_line = lr.line_no;
        } else if (k == "Ks") {
            x.ks = lr.triple(t, t.size() == 2 ? 1 : 3);
        } else if (k == "Ns") {
            x.ns = lr.number(t.size() > 1 ? t[1] : "");
            if (!(x.ns >= 0)) lr.fail("Ns must be >= 0");
        } else if (k == "Ni") {
            cur->ior = lr.number(t.size() > 1 ? t[1] : "");
            if (!(cur->ior > 0)) lr.fail("Ni must be > 0");
        } else if (k == "illum") {
            x.illum = static_cast<int>(lr.number(t.size() > 1 ? t[1] : ""));
        } else if (k == "d") {
            x.d = lr.number(t.back());
        } else if (k == "Tr") {
            x.d = 1 - lr.number(t.back());
        } else if (k == "map_Kd" || k == "map_Ke") {
            std::string note;
            int tex = add_texture(out, texture_path(lr, t, dir, note), true);
            (k == "map_Kd" ? cur->albedo_texture : cur->emission_texture) = tex;
            if (!note.empty()) warn_once(note, note);
        } else if (k == "norm") {
            // A tangent-space normal map (the PBR extension of MTL), linear; -bm scales its x and y.
            std::string note;
            cur->normal_texture = add_texture(out, texture_path(lr, t, dir, note), false);
            if (t.size() == 4 && t[1] == "-bm") {
                cur->normal_scale = static_cast<float>(lr.number(t[2]));
                note.clear();
            }
            if (!note.empty()) warn_once(note, note);
        } else if (k == "map_Bump" || k == "bump" || k == "map_bump" || k == "disp") {
            warn_once("bump", "bump (height) and displacement maps are ignored");
        } else if (k == "map_d") {
            warn_once("alpha", "alpha textures are ignored (the surface is opaque)");
        } else if (k == "map_Ks" || k == "map_Ns" || k == "map_Ka" || k == "refl") {
            warn_once(std::string(k), std::string(k) + " is ignored");
        }
        // Ka, Tf, sharpness and other statements shape nothing this renderer draws.
    }
    for (size_t i = 0; i < extra.size(); ++i) {
        MaterialDesc& m = mtl.materials[first + i];
        cur = &m;
        cur_index = i;
        const Extra& x = extra[i];
        if (m.emission_texture >= 0 && !x.ke_set) m.emission = Vec3(1);
        // Ns (the Phong exponent, 0..1000) as a GGX roughness the way Blender's OBJ exporter and
        // importer pair them: Ns = 1000 (1 - roughness)^2, roughness = 1 - sqrt(Ns / 1000).
        // Without Ns a reflecting or glass material stays perfectly smooth.
        const bool has_ns = x.ns >= 0;
        const float roughness = has_ns ? 1 - std::sqrt(std::min(x.ns, 1000.0f) / 1000) : 0;
        if (x.illum == 3 || x.illum == 5) {
            m.reflectance = is_black(x.ks) ? Vec3(1) : x.ks;
            m.type = has_ns ? MaterialType::Conductor : MaterialType::Mirror;
            m.roughness = roughness;
        } else if (x.illum == 4 || x.illum == 6 || x.illum == 7 || x.illum == 9) {
            m.type = has_ns ? MaterialType::RoughDielectric : MaterialType::Dielectric;
            m.roughness = roughness;
            if (m.ior <= 1) m.ior = 1.5f, warn_once("ior", "Ni missing or <= 1 for glass: 1.5 is used");
        } else if (x.illum == 8) {
            warn_once("illum", "illum 8 (reflection without ray tracing) is drawn diffuse");
        } else if (has_ns && max_component(x.ks) > 0.05f) {
            // A diffuse base under a specular layer: Ks 0.5 (Blender's specular 0.5) is the
            // reflectance of glass at ior 1.5, glTF's specularFactor 1; a coloured Ks tints it.
            m.type = MaterialType::MetallicRoughness;
            m.roughness = roughness;
            const float ks = max_component(vmin(x.ks, Vec3(1)));
            m.specular = std::min(1.0f, 2 * ks);
            m.specular_color = vmin(x.ks, Vec3(1)) / ks;
            m.ior = 1.5f;
        }
        // Smooth mirrors and glass, and GGX metals and rough glass, have no base colour to texture;
        // the smooth ones emit nothing (the GGX ones do, as the surfaces they are).
        const bool smooth = m.type == MaterialType::Mirror || m.type == MaterialType::Dielectric;
        const bool textured = m.type == MaterialType::Diffuse || m.type == MaterialType::MetallicRoughness;
        if ((!textured && m.albedo_texture >= 0) || (smooth && m.emits()))
            warn_once("specular", "a mirror, metal or glass material keeps no texture, and a smooth one no emission");
        if (!textured) m.albedo_texture = -1;
        if (smooth && m.normal_texture >= 0) {
            warn_once("norm", "a mirror or smooth glass keeps no normal map (it reflects about the true surface)");
            m.normal_texture = -1;
        }
        if (smooth) {
            m.emission = Vec3(0);
            m.emission_texture = -1;
        }
        if (m.type == MaterialType::Diffuse && max_component(x.ks) > 0.05f)
            warn_once("ks", "the specular colour Ks is ignored (the surface is diffuse)");
        if (x.d < 1) warn_once("alpha", "transparency d/Tr is ignored (the surface is opaque)");
        if (max_component(m.albedo) > 1 || m.albedo.x < 0 || m.albedo.y < 0 || m.albedo.z < 0) {
            warn_once("kd", "Kd outside [0, 1] is clamped");
            m.albedo = vmin(vmax(m.albedo, Vec3(0)), Vec3(1));
        }
        if (m.emission.x < 0 || m.emission.y < 0 || m.emission.z < 0) {
            lr.line_no = x.ke_line;
            lr.fail("Ke is negative");
        }
        if (max_component(m.emission) > static_cast<float>(limits::kMaxEmission)) {  // as a scene file's radiance
            lr.line_no = x.ke_line;
            lr.fail("Ke is larger than 1e30, the largest radiance accepted");
        }
        if (max_component(m.reflectance) > 1) m.reflectance = vmin(m.reflectance, Vec3(1));
    }
    for (size_t i = 0; i < notes.size(); ++i) {
        if (notes[i].empty()) continue;
        std::string all;
        for (const std::string& n : notes[i]) all += (all.empty() ? "" : "; ") + n;
        out.warnings.push_back(path + ": material '" + mtl.materials[first + i].name + "': " + all);
    }
}

// A face corner: indices into v, vt and vn (-1: none). Faces are read as corner IDs into the
// table of distinct corners, so a file that repeats its corners costs its distinct ones.
struct Corner {
    int64_t v, t, n;
    bool operator==(const Corner& o) const { return v == o.v && t == o.t && n == o.n; }
};
struct CornerHash {
    size_t operator()(const Corner& k) const { return static_cast<size_t>(xxh64_of(&k, sizeof k)); }
};

// The faces seen so far, by their corners (whatever corner comes first) and material: a face
// written again is drawn once. Open addressing over triangle numbers (4 bytes a slot, at most
// half full): a hash set of the triples would cost ten times that on a large mesh.
class FaceSet {
public:
    FaceSet(const std::vector<uint32_t>& corners, const std::vector<int32_t>& material)
        : corners_(corners), material_(material) {
        size_t cap = 16;
        while (cap < 2 * material.size()) cap *= 2;
        slots_.assign(cap, kEmpty);
    }
    // True when triangle t repeats one inserted before; else inserts it.
    bool repeats(uint32_t t) {
        const Key k = key(t);
        size_t i = static_cast<size_t>(xxh64_of(&k, sizeof k)) & (slots_.size() - 1);
        while (slots_[i] != kEmpty) {
            if (key(slots_[i]) == k) return true;
            i = (i + 1) & (slots_.size() - 1);
        }
        slots_[i] = t;
        return false;
    }

private:
    static constexpr uint32_t kEmpty = UINT32_MAX;
    struct Key {
        uint32_t c[3];
        int32_t material;
        bool operator==(const Key& o) const {
            return c[0] == o.c[0] && c[1] == o.c[1] && c[2] == o.c[2] && material == o.material;
        }
    };
    // Rotated so that the smallest corner comes first: the same face, the same front.
    Key key(uint32_t t) const {
        const uint32_t* c = &corners_[3 * static_cast<size_t>(t)];
        const int r = c[0] <= c[1] && c[0] <= c[2] ? 0 : c[1] <= c[2] ? 1 : 2;
        return {{c[r], c[(r + 1) % 3], c[(r + 2) % 3]}, material_[t]};
    }
    const std::vector<uint32_t>& corners_;
    const std::vector<int32_t>& material_;
    std::vector<uint32_t> slots_;
};

}  // namespace

ImportedFile read_obj_mtl(const std::string& path, bool read_materials) {
    ImportedFile out;
    const std::string text = read_text(path, "mesh file");
    if (text.empty()) throw InputError(path + ": the mesh file is empty");
    out.files.push_back(path);
    const fs::path dir = fs::path(path).parent_path();
    LineReader lr{path};
    std::vector<Vec3> v, vn;
    std::vector<float> vt;
    MtlResult mtl;
    int current = -1;  // material of the faces that follow (-1: the default)
    bool any_normals = false, any_uvs = false;
    std::set<std::string> warned;
    // Faces first gather corners; output vertices are made per distinct (v, vt, vn).
    std::unordered_map<Corner, uint32_t, CornerHash> corner_id;
    std::vector<Corner> corners;          // distinct, in the order they first appear
    std::vector<uint32_t> face;
    std::vector<uint32_t> tri_corners;    // 3 per triangle: into `corners`
    std::vector<int32_t> tri_material;
    size_t pos = 0;
    while (pos < text.size()) {
        size_t end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        std::string_view line(text.data() + pos, end - pos);
        pos = end + 1;
        ++lr.line_no;
        if (line.find('\0') != std::string_view::npos) lr.fail("holds a NUL byte: not an OBJ text file");
        auto t = tokens_of(line);
        if (t.empty() || t[0][0] == '#') continue;
        const std::string_view k = t[0];
        if (k == "v") {
            v.push_back(lr.triple(t, 3));
        } else if (k == "vn") {
            vn.push_back(lr.triple(t, 3));
        } else if (k == "vt") {
            if (t.size() < 2) lr.fail("'vt' needs at least one number");
            float uu = lr.number(t[1]), vv = t.size() > 2 ? lr.number(t[2]) : 0;
            for (size_t i = 3; i < t.size(); ++i) lr.number(t[i]);
            vt.push_back(uu);
            vt.push_back(1 - vv);  // OBJ's v = 0 is the image's bottom row; ours the top
        } else if (k == "f") {
            if (t.size() < 4) lr.fail("a face needs at least 3 corners");
            face.clear();
            for (size_t i = 1; i < t.size(); ++i) {
                std::string_view c = t[i];
                size_t s1 = c.find('/');
                std::string_view a = c.substr(0, s1), b, n;
                if (s1 != std::string_view::npos) {
                    std::string_view r = c.substr(s1 + 1);
                    size_t s2 = r.find('/');
                    b = r.substr(0, s2);
                    if (s2 != std::string_view::npos) n = r.substr(s2 + 1);
                }
                Corner cc{lr.index(a, v.size(), "vertex"), -1, -1};
                if (!b.empty()) cc.t = lr.index(b, vt.size() / 2, "texture coordinate");
                if (!n.empty()) cc.n = lr.index(n, vn.size(), "normal");
                auto [it, fresh] = corner_id.try_emplace(cc, static_cast<uint32_t>(corners.size()));
                if (fresh) corners.push_back(cc);
                face.push_back(it->second);
            }
            for (size_t i = 1; i + 1 < face.size(); ++i) {  // a fan over the polygon
                tri_corners.insert(tri_corners.end(), {face[0], face[i], face[i + 1]});
                tri_material.push_back(current);
            }
        } else if (k == "usemtl") {
            if (!read_materials) continue;
            std::string name = rest_of(line, "usemtl");
            auto it = mtl.index.find(name);
            if (it == mtl.index.end()) {
                if (warned.insert("usemtl " + name).second)
                    out.warnings.push_back(path + ":" + std::to_string(lr.line_no) + ": usemtl '" + name +
                                           "' is not in any material library: the default diffuse material is used");
                current = -1;
            } else {
                current = it->second;
            }
        } else if (k == "mtllib") {
            if (!read_materials) continue;
            // One name that may hold spaces, or several names separated by spaces.
            std::string name = rest_of(line, "mtllib");
            if (name.empty()) lr.fail("mtllib names no file");
            auto resolve = [&](const std::string& n) {
                fs::path p(n);
                if (p.is_relative()) p = dir / p;
                return p.lexically_normal();
            };
            std::error_code ec;
            std::vector<fs::path> libs;
            if (fs::is_regular_file(resolve(name), ec)) {
                libs.push_back(resolve(name));
            } else {
                for (size_t i = 1; i < t.size(); ++i) libs.push_back(resolve(std::string(t[i])));
            }
            for (const fs::path& p : libs)
                if (fs::exists(p, ec) && !fs::is_regular_file(p, ec)) {  // there, but no file: say what it is
                    try {
                        check_input_file(p.string(), kMaxTextBytes, p.string(), "material library (.mtl)");
                    } catch (const InputError& e) {
                        lr.fail(std::string("mtllib names ") + e.what());
                    }
                } else if (!fs::is_regular_file(p, ec)) {
                    lr.fail("mtllib names a missing material library: " + p.string() +
                            (libs.size() > 1 ? " (nor is " + resolve(name).string() + " a file)" : ""));
                }
            for (const fs::path& p : libs) read_mtl(p.string(), out, mtl);
        } else if (k == "l" || k == "p") {
            if (warned.insert("lp").second)
                out.warnings.push_back(path + ": lines and points (l, p) are ignored");
        } else if (k == "o" || k == "g" || k == "s" || k == "vp" || k == "cstype" || k == "deg" ||
                   k == "curv" || k == "surf" || k == "parm" || k == "end" || k == "mg") {
            continue;
        } else if (warned.insert("kw " + std::string(k)).second) {
            out.warnings.push_back(path + ":" + std::to_string(lr.line_no) + ": unknown statement '" +
                                   std::string(k.substr(0, 40)) + "' is ignored");
        }
    }
    if (tri_corners.empty()) throw InputError(path + ": the mesh has no faces");
    corner_id = {};  // (its memory, before the mesh is made)
    for (const Corner& c : corners) {
        any_normals |= c.n >= 0;
        any_uvs |= c.t >= 0;
    }
    // Materials: the library's, then a default for faces without one.
    out.materials = mtl.materials;
    int default_material = -1;
    MeshData& m = out.mesh;
    constexpr uint32_t kNoVertex = UINT32_MAX;
    std::vector<uint32_t> vertex_of(corners.size(), kNoVertex);  // a corner's output vertex
    FaceSet seen(tri_corners, tri_material);
    size_t repeated = 0;
    for (size_t tri = 0; tri < tri_material.size(); ++tri) {
        const uint32_t* id = &tri_corners[3 * tri];
        const Corner c[3] = {corners[id[0]], corners[id[1]], corners[id[2]]};
        Vec3 a = v[static_cast<size_t>(c[0].v)], b = v[static_cast<size_t>(c[1].v)], d = v[static_cast<size_t>(c[2].v)];
        Vec3 fn = cross(b - a, d - a);
        float area2 = length(fn);
        if (!(area2 > 0) || !std::isfinite(area2)) continue;  // degenerate: no area, no light
        if (seen.repeats(static_cast<uint32_t>(tri))) {  // the same face again: drawn once
            ++repeated;
            continue;
        }
        bool flat = any_normals && (c[0].n < 0 || c[1].n < 0 || c[2].n < 0);
        uint32_t idx[3];
        for (int k = 0; k < 3; ++k) {
            // A corner of a face without normals gets its own vertex with the face's normal.
            const bool fresh = flat || vertex_of[id[k]] == kNoVertex;
            if (fresh) {
                if (!flat) vertex_of[id[k]] = static_cast<uint32_t>(m.positions.size());
                idx[k] = static_cast<uint32_t>(m.positions.size());
                m.positions.push_back(v[static_cast<size_t>(c[k].v)]);
                if (any_normals) {
                    Vec3 n = flat ? fn / area2 : vn[static_cast<size_t>(c[k].n)];
                    float l = length(n);
                    m.normals.push_back(l > 0 ? n / l : fn / area2);
                }
                if (any_uvs) {
                    m.uvs.push_back(c[k].t >= 0 ? vt[2 * static_cast<size_t>(c[k].t)] : 0.0f);
                    m.uvs.push_back(c[k].t >= 0 ? vt[2 * static_cast<size_t>(c[k].t) + 1] : 0.0f);
                }
            } else {
                idx[k] = vertex_of[id[k]];
            }
        }
        m.indices.insert(m.indices.end(), {idx[0], idx[1], idx[2]});
        int mat = tri_material[tri];
        if (mat < 0) {
            if (default_material < 0) {
                MaterialDesc d;
                d.name = "default";
                default_material = static_cast<int>(out.materials.size());
                out.materials.push_back(d);
            }
            mat = default_material;
        }
        m.tri_material.push_back(mat);
    }
    if (m.indices.empty()) throw InputError(path + ": the mesh has no triangles with area");
    if (repeated > 0)
        out.warnings.push_back(path + ": " + std::to_string(repeated) +
                               " faces repeat an earlier face (the same corners and material): each is drawn once");
    m.positions.shrink_to_fit();
    m.normals.shrink_to_fit();
    m.uvs.shrink_to_fit();
    m.indices.shrink_to_fit();
    m.tri_material.shrink_to_fit();
    return out;
}

}  // namespace sl
