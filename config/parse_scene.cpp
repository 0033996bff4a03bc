#include "config/parse_scene.h"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>

#include "config/default_scene.h"
#include "config/input_file.h"
#include "config/json_reader.h"
#include "config/limits.h"
#include "config/pulse_width.h"
#include "config/scene_keys.h"
#include "config/text_util.h"
#include "foundation/errors.h"
#include "config/sun_desc.h"

namespace sl {

namespace fs = std::filesystem;

namespace {

constexpr size_t kMaxSceneFileBytes = size_t(64) << 20;  // a scene file is small; meshes are apart

// "principled" (a gltf shape, a metallic_roughness material): how the diffuse base is drawn.
PrincipledBase principled_choice(const JsonObject& o) {
    return static_cast<PrincipledBase>(o.choice("principled", {"energy_conserving", "blender3"}));
}

// Turns checked JSON into a SceneDesc, converting lengths to meters on the way.
class SceneParser {
public:
    SceneParser(const std::string& source, const std::string& base_dir)
        : source_(source), base_dir_(base_dir) {}

    SceneDesc parse(const Json& root) {
        JsonObject top(root, "", source_);
        top.expect_keys(scene_keys_of(""));
        scene_.source = source_;
        // Units first: every length below depends on them. Time before emission: the pulse
        // width is checked against the frame width.
        if (top.has("units")) parse_units(top.object("units"));
        parse_camera(top.object("camera"));
        if (top.has("materials")) parse_materials(top.object("materials"));
        if (top.has("shapes"))
            for_each_element(top, "shapes",
                             [&](const JsonObject& s) { scene_.shapes.push_back(shape(s)); });
        // Imported files and emissive materials may bring the light: then "lights" may be
        // omitted or empty, and whether the scene has any light is checked once the files are
        // read (core/import). (Only a glTF file, or a mesh that keeps its own materials, can
        // bring light of its own.)
        bool imports = false;
        for (const ShapeDesc& sh : scene_.shapes)
            imports |= sh.type == ShapeType::Gltf || (sh.type == ShapeType::Mesh && sh.material < 0) ||
                       (sh.material >= 0 && scene_.materials[static_cast<size_t>(sh.material)].emits());
        if (!imports || top.has("lights"))
            for_each_element(top, "lights",
                             [&](const JsonObject& l) { scene_.lights.push_back(light(l)); });
        if (!imports) check_lights(top);
        if (top.has("medium")) parse_medium(top.object("medium"));
        if (top.has("time")) parse_time(top.object("time"));
        if (top.has("emission")) parse_emission(top.object("emission"));
        if (top.has("render")) parse_render(top.object("render"));
        scene_.input_files = std::move(inputs_);
        return std::move(scene_);
    }

private:
    static unsigned kind_of(const fs::path& p) {
        struct stat st {};
        return ::stat(p.c_str(), &st) == 0 ? st.st_mode : 0u;
    }

    template <class F>
    void for_each_element(const JsonObject& parent, std::string_view key, F&& f) const {
        const Json& array = parent.at(key);
        if (!array.is_array())
            parent.fail(key, "must be an array [...], got " + describe_json(array));
        for (size_t i = 0; i < array.size(); ++i)
            f(JsonObject(array[i], element_path(parent.path_of(key), i), source_));
    }

    // --- values -----------------------------------------------------------------------------

    // A number stored as float, re-checked after rounding (0.99999999999 rounds to 1).
    static float number_f(const JsonObject& o, std::string_view key, Range r, float dflt) {
        if (!o.has(key)) return dflt;
        double v = o.number(key, r);
        float f = static_cast<float>(v);
        if (!r.contains(f))
            o.fail(key,
                   "must be " + r.describe() + " in single precision, got " + format_number(v));
        return f;
    }

    // A triple stored as float; large values must stay finite.
    static Vec3 to_vec3(const JsonObject& o, std::string_view key, const Triple& t) {
        Vec3 v{static_cast<float>(t[0]), static_cast<float>(t[1]), static_cast<float>(t[2])};
        if (!is_finite(v)) o.fail(key, "is too large for single precision");
        return v;
    }

    // A length in the file's units as meters, within the global bound.
    float meters(const JsonObject& o, std::string_view key, double v) const {
        double m = v * scale_;
        if (!(std::abs(m) <= limits::kMaxLength))
            o.fail(key, "is " + format_number(m) + " m after units; lengths must be within +-" +
                            format_number(limits::kMaxLength) + " m");
        return static_cast<float>(m);
    }

    // A scalar length: the range applies to the value as written, and a positive length
    // must not round to zero meters.
    float scalar_length(const JsonObject& o, std::string_view key, Range r) const {
        double v = o.number(key, r);
        float m = meters(o, key, v);
        if (v > 0 && m == 0) o.fail(key, "is too small: rounds to 0 m");
        return m;
    }

    Vec3 point(const JsonObject& o, std::string_view key) const {
        Triple t = o.triple(key, Range::any());
        return {meters(o, key, t[0]), meters(o, key, t[1]), meters(o, key, t[2])};
    }

    // A unit direction (normalized in double, so that huge components do not overflow).
    static Vec3 direction(const JsonObject& o, std::string_view key) {
        Triple t = o.triple(key, Range::any());
        double len = std::hypot(t[0], t[1], t[2]);
        if (!(len > 0) || !std::isfinite(len))
            o.fail(key, "must be a non-zero direction, got " + describe_json(o.at(key)));
        return {static_cast<float>(t[0] / len), static_cast<float>(t[1] / len),
                static_cast<float>(t[2] / len)};
    }

    // Power, radiance, ambient: non-negative RGB.
    static Vec3 color(const JsonObject& o, std::string_view key) {
        return to_vec3(o, key, o.triple(key, Range::closed(0, limits::kMaxEmission)));
    }

    // A quad spans a parallelogram; its edges must be non-zero and not parallel.
    static void check_quad(const JsonObject& o, Vec3 e1, Vec3 e2) {
        if (!(length(cross(e1, e2)) > 1e-6f * length(e1) * length(e2)))
            o.fail("edge2", "degenerate quad of zero area: edge1 and edge2 are zero or parallel");
    }

    static void check_box(const JsonObject& o, Vec3 lo, Vec3 hi) {
        for (int a = 0; a < 3; ++a)
            if (!(lo[a] < hi[a]))
                o.fail("max", "must be greater than min on every axis, got min " +
                                  describe_json(o.at("min")) + " and max " +
                                  describe_json(o.at("max")));
    }

    // --- sections ---------------------------------------------------------------------------

    void parse_units(const JsonObject& u) {
        u.expect_keys(scene_keys_of("units"));
        scale_ = u.number("meters_per_unit", Range::positive(), 1.0);
        scene_.meters_per_unit = scale_;
    }

    void parse_camera(const JsonObject& c) {
        c.expect_keys(scene_keys_of("camera"));
        CameraDesc& cam = scene_.camera;
        cam.position = point(c, "position");
        cam.look_at = point(c, "look_at");
        if (c.has("up")) cam.up = direction(c, "up");
        cam.vfov_deg = number_f(c, "vfov_deg", Range::open(0, 180), cam.vfov_deg);
        cam.width = static_cast<int>(c.integer("width", 1, limits::kMaxImageSide, cam.width));
        cam.height = static_cast<int>(c.integer("height", 1, limits::kMaxImageSide, cam.height));
        Vec3 forward = cam.look_at - cam.position;
        if (!(length(forward) > 0)) c.fail("look_at", "must differ from camera.position");
        if (!(length(cross(normalize(forward), cam.up)) > 1e-5f))
            c.fail("up", "must not be parallel to the view direction look_at - position");
    }

    void parse_materials(const JsonObject& ms) {
        for (const auto& item : ms.json().items()) {
            if (item.key().empty()) ms.fail_here("a material name must not be empty");
            JsonObject m(item.value(), ms.path_of(item.key()), source_);
            MaterialDesc d;
            d.name = item.key();
            d.type =
                static_cast<MaterialType>(m.choice("type", {"diffuse", "mirror", "dielectric", "conductor",
                                                            "rough_dielectric", "metallic_roughness"}));
            const Range unit = Range::closed(0, 1);
            switch (d.type) {
                case MaterialType::Diffuse:
                    m.expect_keys(scene_keys_of("materials", "diffuse"));
                    if (m.has("albedo")) d.albedo = to_vec3(m, "albedo", m.triple("albedo", unit));
                    break;
                case MaterialType::Mirror:
                    m.expect_keys(scene_keys_of("materials", "mirror"));
                    if (m.has("reflectance"))
                        d.reflectance = to_vec3(m, "reflectance", m.triple("reflectance", unit));
                    break;
                case MaterialType::Dielectric:
                    m.expect_keys(scene_keys_of("materials", "dielectric"));
                    d.ior = number_f(m, "ior", Range::positive(), d.ior);
                    break;
                case MaterialType::Conductor:
                    m.expect_keys(scene_keys_of("materials", "conductor"));
                    d.roughness = number_f(m, "roughness", unit, d.roughness);
                    if (m.has("reflectance") && (m.has("eta") || m.has("k")))
                        m.fail("reflectance", "give either reflectance (at normal incidence) or eta and k, not both");
                    if (m.has("eta") != m.has("k"))
                        m.fail(m.has("eta") ? "eta" : "k", "a complex index needs both eta and k");
                    if (m.has("reflectance")) d.reflectance = to_vec3(m, "reflectance", m.triple("reflectance", unit));
                    if (m.has("eta")) {
                        d.complex_ior = true;
                        d.eta = to_vec3(m, "eta", m.triple("eta", Range::open(0, 100)));
                        d.k = to_vec3(m, "k", m.triple("k", Range::closed(0, 100)));
                    }
                    break;
                case MaterialType::RoughDielectric:
                    m.expect_keys(scene_keys_of("materials", "rough_dielectric"));
                    d.ior = number_f(m, "ior", Range::open(0, 100), d.ior);
                    if (d.ior == 1) m.fail("ior", "must differ from 1 (an index of 1 is no interface)");
                    d.roughness = number_f(m, "roughness", unit, d.roughness);
                    break;
                case MaterialType::MetallicRoughness:
                    m.expect_keys(scene_keys_of("materials", "metallic_roughness"));
                    if (m.has("base_color")) d.albedo = to_vec3(m, "base_color", m.triple("base_color", unit));
                    d.metallic = number_f(m, "metallic", unit, d.metallic);
                    d.roughness = number_f(m, "roughness", unit, d.roughness);
                    d.ior = number_f(m, "ior", Range::open(0, 100), d.ior);
                    d.specular = number_f(m, "specular", unit, d.specular);
                    d.transmission = number_f(m, "transmission", unit, d.transmission);
                    if (d.transmission > 0 && d.ior == 1)
                        m.fail("ior", "must differ from 1 when the material transmits (an index of 1 is no interface)");
                    if (m.has("principled")) d.principled = principled_choice(m);
                    break;
            }
            // Any surface may emit (W sr^-1 m^-2 from its front), as imported emissive materials do.
            if (m.has("emission")) d.emission = color(m, "emission");
            material_index_[d.name] = static_cast<int>(scene_.materials.size());
            scene_.materials.push_back(d);
        }
    }

    int material_ref(const JsonObject& s) const {
        std::string name = s.string("material");
        auto it = material_index_.find(name);
        if (it != material_index_.end()) return it->second;
        std::string defined;
        for (const MaterialDesc& m : scene_.materials)
            defined += (defined.empty() ? "" : ", ") + m.name;
        s.fail("material",
               "no material named \"" + name + "\" (" +
                   (defined.empty() ? "no materials are defined" : "defined: " + defined) + ")");
    }

    std::string mesh_path(const JsonObject& s) const {
        std::string file = s.string("file");
        if (file.empty() || file.find('\0') != std::string::npos)
            s.fail("file", "must be a file path, got " + describe_json(s.at("file")));
        fs::path p(file);
        if (p.is_relative()) p = base_dir_ / p;
        std::error_code ec;
        p = fs::absolute(p, ec).lexically_normal();
        fs::file_status st = fs::status(p, ec);
        if (!fs::exists(st)) s.fail("file", "mesh file not found: " + p.string());
        if (fs::is_directory(st)) s.fail("file", "is a directory, not a mesh file: " + p.string());
        if (!fs::is_regular_file(st))  // a FIFO would block, /dev/zero never end
            s.fail("file", "is " + file_kind_name(kind_of(p)) + ", not a mesh file (only regular files are read): " +
                               p.string());
        inputs_.push_back(p.string());
        return p.string();
    }

    ShapeDesc shape(const JsonObject& s) const {
        ShapeDesc d;
        d.type = static_cast<ShapeType>(s.choice("type", {"quad", "box", "sphere", "mesh", "gltf"}));
        switch (d.type) {
            case ShapeType::Quad:
                s.expect_keys(scene_keys_of("shapes", "quad"));
                d.corner = point(s, "corner");
                d.edge1 = point(s, "edge1");
                d.edge2 = point(s, "edge2");
                check_quad(s, d.edge1, d.edge2);
                break;
            case ShapeType::Box:
                s.expect_keys(scene_keys_of("shapes", "box"));
                d.min = point(s, "min");
                d.max = point(s, "max");
                check_box(s, d.min, d.max);
                break;
            case ShapeType::Sphere:
                s.expect_keys(scene_keys_of("shapes", "sphere"));
                d.center = point(s, "center");
                d.radius = scalar_length(s, "radius", Range::positive());
                break;
            case ShapeType::Mesh:
            case ShapeType::Gltf:
                s.expect_keys(scene_keys_of("shapes", d.type == ShapeType::Mesh ? "mesh" : "gltf"));
                d.file = mesh_path(s);
                if (s.has("translate")) d.translate = point(s, "translate");
                // The OBJ's coordinates are in the file's units too: the scale carries them.
                d.scale = s.has("scale") ? scalar_length(s, "scale", Range::positive())
                                         : meters(s, "scale", 1.0);
                if (s.has("rotate_deg"))
                    d.rotate_deg = to_vec3(s, "rotate_deg", s.triple("rotate_deg", Range::any()));
                if (d.type == ShapeType::Gltf && s.has("light_units"))
                    d.light_units = static_cast<LightUnits>(s.choice("light_units", {"photometric", "radiometric"}));
                if (d.type == ShapeType::Gltf && s.has("principled")) {
                    // It chooses how the file's own materials are drawn: an entry that names one
                    // of the scene's materials uses that material's own "principled".
                    if (s.has("material"))
                        s.fail("principled", "applies to the file's own materials, and this entry names \"material\" "
                                             "(give that material its own \"principled\")");
                    d.principled = principled_choice(s);
                }
                break;
        }
        // A mesh or glTF file without "material" keeps its own materials.
        const bool imported = d.type == ShapeType::Mesh || d.type == ShapeType::Gltf;
        d.material = imported && !s.has("material") ? -1 : material_ref(s);
        // Emitters are sampled as triangles (core/emissive_triangles.h): a sphere has none.
        if (d.type == ShapeType::Sphere && scene_.materials[static_cast<size_t>(d.material)].emits())
            s.fail("material", "names an emissive material, and a sphere cannot emit (use a quad, box or mesh)");
        return d;
    }

    LightDesc light(const JsonObject& l) const {
        LightDesc d;
        d.type = static_cast<LightType>(l.choice("type", {"point", "quad", "spot", "laser", "sun"}));
        switch (d.type) {
            case LightType::Point:
                l.expect_keys(scene_keys_of("lights", "point"));
                d.position = point(l, "position");
                d.power = color(l, "power");
                break;
            case LightType::Quad:
                l.expect_keys(scene_keys_of("lights", "quad"));
                d.corner = point(l, "corner");
                d.edge1 = point(l, "edge1");
                d.edge2 = point(l, "edge2");
                check_quad(l, d.edge1, d.edge2);
                d.radiance = color(l, "radiance");
                break;
            case LightType::Spot:
                l.expect_keys(scene_keys_of("lights", "spot"));
                d.position = point(l, "position");
                d.direction = direction(l, "direction");
                d.cone_deg = number_f(l, "cone_deg", Range{limits::kMinSpotConeDeg, 180, false, false}, d.cone_deg);
                d.power = color(l, "power");
                break;
            case LightType::Laser:
                l.expect_keys(scene_keys_of("lights", "laser"));
                d.position = point(l, "position");
                d.direction = direction(l, "direction");
                if (l.has("radius")) d.radius = scalar_length(l, "radius", Range::positive());
                d.power = color(l, "power");
                break;
            case LightType::Sun:
                parse_sun(l, d);
                break;
        }
        return d;
    }

    // A sun: where its light goes, its angular diameter and either the irradiance on a plane
    // facing it (W/m^2) or the radiance of its disc (W sr^-1 m^-2).
    static void parse_sun(const JsonObject& l, LightDesc& d) {
        l.expect_keys(scene_keys_of("lights", "sun"));
        d.direction = direction(l, "direction");
        d.angle_deg = number_f(l, "angle_deg", Range::closed(0, limits::kMaxSunAngleDeg), d.angle_deg);
        const bool e = l.has("irradiance"), r = l.has("radiance");
        if (e == r) l.fail("irradiance", "a sun needs exactly one of \"irradiance\" (W/m^2) or \"radiance\" (W/sr/m^2)");
        if (e) {
            d.irradiance = color(l, "irradiance");
        } else {
            if (!(d.angle_deg > 0))
                l.fail("radiance", "needs \"angle_deg\" > 0 (a sun of no size has no finite radiance); give \"irradiance\"");
            d.irradiance = sun_irradiance_from_radiance(color(l, "radiance"), d.angle_deg);
        }
    }

    // A scene needs light: at least one light, and not all of them dark.
    void check_lights(const JsonObject& top) const {
        if (scene_.lights.empty()) top.fail("lights", "must contain at least one light");
        for (const LightDesc& l : scene_.lights)
            if (!is_black(l.type == LightType::Quad  ? l.radiance
                          : l.type == LightType::Sun ? l.irradiance
                                                     : l.power))
                return;
        top.fail("lights", "every light has zero power or radiance; at least one must emit");
    }

    // Medium coefficients are per unit length: per meter, they divide by the scale.
    Vec3 per_meter(const JsonObject& m, std::string_view key) const {
        Triple t = m.number_or_triple(key, Range::non_negative(), {0, 0, 0});
        for (double& c : t) c /= scale_;
        return to_vec3(m, key, t);
    }

    void parse_medium(const JsonObject& m) {
        m.expect_keys(scene_keys_of("medium"));
        MediumDesc& md = scene_.medium;
        md.present = true;
        md.sigma_a = per_meter(m, "sigma_a");
        md.sigma_s = per_meter(m, "sigma_s");
        md.g = number_f(m, "g", Range::open(-1, 1), md.g);
        if (m.has("bounds")) {
            JsonObject b = m.object("bounds");
            b.expect_keys(scene_keys_of("medium.bounds"));
            md.has_bounds = true;
            md.bounds_min = point(b, "min");
            md.bounds_max = point(b, "max");
            check_box(b, md.bounds_min, md.bounds_max);
        }
    }

    void parse_time(const JsonObject& t) {
        t.expect_keys(scene_keys_of("time"));
        TimeDesc& td = scene_.time;
        td.start_ns = t.number("start_ns", Range::any(), td.start_ns);
        td.end_ns = t.number("end_ns", Range::any(), td.end_ns);
        td.frames = static_cast<int>(t.integer("frames", 1, limits::kMaxFrames, td.frames));
        td.fps = t.number("fps", Range::closed(limits::kMinFps, limits::kMaxFps), td.fps);
        if (!(td.end_ns > td.start_ns))
            t.fail("end_ns", "must be greater than start_ns (" + format_number(td.start_ns) +
                                 "), got " + format_number(td.end_ns));
        if (!Timeline{td.start_ns, td.end_ns, td.frames}.has_valid_delta())
            t.fail("end_ns", "end_ns - start_ns is out of range");
    }

    void parse_emission(const JsonObject& e) {
        e.expect_keys(scene_keys_of("emission"));
        EmissionDesc& ed = scene_.emission;
        ed.mode = static_cast<EmissionMode>(e.choice("mode", {"constant", "pulse"}, 0));
        if (e.has("width_ns")) {
            if (ed.mode != EmissionMode::Pulse)
                e.fail("width_ns", "applies only to \"mode\": \"pulse\"");
            ed.width_ns = e.number("width_ns", Range::positive());
        }
        if (auto problem = check_pulse_width(scene_.time, ed)) e.fail("width_ns", *problem);
    }

    void parse_render(const JsonObject& r) {
        r.expect_keys(scene_keys_of("render"));
        RenderDesc& rd = scene_.render;
        rd.passes = static_cast<int>(r.integer("passes", 1, limits::kMaxPasses, rd.passes));
        rd.photons_per_pass =
            r.integer("photons_per_pass", 1, limits::kMaxPhotonsPerPass, rd.photons_per_pass);
        rd.max_depth = static_cast<int>(r.integer("max_depth", 1, limits::kMaxDepth, rd.max_depth));
        if (r.has("radius")) rd.radius = scalar_length(r, "radius", Range::non_negative());
        rd.alpha = number_f(r, "alpha", Range::open(0, 1), rd.alpha);
        rd.camera_tof = r.boolean("camera_tof", rd.camera_tof);
        rd.seed = r.unsigned_integer("seed", rd.seed);
        if (r.has("ambient")) rd.ambient = color(r, "ambient");
    }

    const std::string& source_;
    fs::path base_dir_;
    double scale_ = 1;  // meters per file unit
    mutable std::vector<std::string> inputs_;  // every file the scene reads, for output checks
    SceneDesc scene_;
    std::map<std::string, int> material_index_;
};

}  // namespace

SceneDesc parse_scene_text(const std::string& text, const std::string& source_name,
                           const std::string& base_dir) {
    Json root = parse_json_text(text, source_name);
    return SceneParser(source_name, base_dir).parse(root);
}

SceneDesc parse_scene_file(const std::string& path) {
    // Only a regular file of at most 64 MiB is read: a FIFO or a device cannot hang us.
    const std::string text = read_input_file(path, kMaxSceneFileBytes, printable(path), "scene file");
    SceneDesc scene = parse_scene_text(text, path, fs::path(path).parent_path().string());
    scene.input_files.insert(scene.input_files.begin(), path);
    return scene;
}

SceneDesc parse_default_scene() {
    return parse_scene_text(default_scene_json(), "<default>", "");
}

}  // namespace sl
