#include "pipeline/scene_info.h"

#include <algorithm>
#include <cstdio>
#include <string_view>

#include "foundation/errors.h"
#include "core/import/resolve_imports.h"
#include "pipeline/memory_plan.h"
#include "pipeline/scene_checks.h"
#include "stages/render/render_context.h"

namespace sl {
namespace {

std::string fixed(double v, int decimals) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

const char* light_type_name(LightType t) {
    switch (t) {
        case LightType::Point: return "point";
        case LightType::Quad: return "quad";
        case LightType::Spot: return "spot";
        case LightType::Laser: return "laser";
        case LightType::Sun: return "sun";
    }
    return "light";
}

// An imported file by its name, a scene file's emissive quad or box by its place.
std::string emitter_name(const ShapeDesc& sh, size_t i) {
    if (!sh.file.empty()) return sh.file;
    return "shapes[" + std::to_string(i) + "] (" + (sh.type == ShapeType::Box ? "box" : "quad") + ")";
}

std::string watts(double w) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.4g W", w);
    return buf;
}

// Metallic-roughness materials and how many of them draw Cycles 3.x's Principled v1
// ("principled": "blender3": said by the scene, --gltf-principled, or a file Blender 3.x wrote).
std::pair<size_t, size_t> principled_counts(const SceneDesc& s) {
    size_t all = 0, blender3 = 0;
    for (const MaterialDesc& m : s.materials)
        if (m.type == MaterialType::MetallicRoughness) {
            ++all;
            if (m.principled == PrincipledBase::Blender3) ++blender3;
        }
    return {all, blender3};
}

// Every light's power in watts (the mean of its RGB channels), the file it came from, and the
// emissive surfaces of every imported file.
void print_light_powers(std::ostream& out, const SceneDesc& s, Vec3 size) {
    std::vector<const ShapeDesc*> from(s.lights.size(), nullptr);
    for (const ShapeDesc& sh : s.shapes)
        for (int i = sh.first_light; i < sh.first_light + sh.light_count; ++i) from[static_cast<size_t>(i)] = &sh;
    const char* label = "power:      ";
    for (size_t i = 0; i < s.lights.size(); ++i) {
        const LightDesc& l = s.lights[i];
        out << label << "lights[" << i << "] " << light_type_name(l.type) << ": ";
        label = "            ";
        if (l.type == LightType::Sun) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "%.4g W/m^2", (double(l.irradiance.x) + l.irradiance.y + l.irradiance.z) / 3);
            out << buf << ", " << watts(light_watts(l, size)) << " through the scene's cross-section";
        } else {
            out << watts(light_watts(l, size));
        }
        if (from[i]) out << " (from " << from[i]->file << ")";
        out << "\n";
    }
    for (size_t i = 0; i < s.shapes.size(); ++i)
        if (const double w = emissive_watts(s, s.shapes[i]); w > 0) {
            out << label << "emissive surfaces of " << emitter_name(s.shapes[i], i) << ": " << watts(w) << "\n";
            label = "            ";
        }
}

}  // namespace

void print_scene_info(std::ostream& out, std::ostream& err, const SceneDesc& s, const RunOptions& options) {
    const int ranks = std::max(1, options.ranks);  // with MPI ranks, memory is per rank
    const double delta = timeline_of(s).delta();
    RenderContext ctx(s);
    SceneFacts f = scene_facts(ctx);
    out << "scene:      " << s.source << "\n"
        << "image:      " << s.camera.width << " x " << s.camera.height << "\n"
        << "shapes:     " << s.shapes.size() << ", materials: " << s.materials.size()
        << ", lights: " << s.lights.size() << (s.medium.present ? ", with a medium" : ", vacuum") << "\n"
        << "geometry:   " << f.triangles << " triangles, " << f.spheres << " spheres\n"
        << "size:       " << fixed(f.size.x, 3) << " x " << fixed(f.size.y, 3) << " x " << fixed(f.size.z, 3)
        << " m (units: " << s.meters_per_unit << " m per unit); light crosses its diagonal of "
        << fixed(f.diagonal_m, 3) << " m in " << fixed(f.crossing_ns, 2) << " ns\n"
        << "time:       " << s.time.start_ns << " to " << s.time.end_ns << " ns, " << s.time.frames
        << " frames of " << delta << " ns (" << delta * kSpeedOfLight << " m of light), " << s.time.fps << " fps\n"
        << "arrivals:   ";
    if (f.first_arrival_ns) {
        out << "light reflected toward the camera arrives from " << fixed(*f.first_arrival_ns, 2) << " ns";
        if (f.last_direct_arrival_ns)
            out << "; direct light has reached everything it lights by " << fixed(*f.last_direct_arrival_ns, 2)
                << " ns";
        out << (s.render.camera_tof ? " (camera leg included)" : " (camera leg not included)") << "\n";
    } else {
        out << "no light shines straight on anything the camera sees (only bounced light will)\n";
    }
    out << "emission:   " << (s.emission.mode == EmissionMode::Constant ? "constant" : "pulse") << "\n"
        << "render:     " << s.render.passes << " passes x " << s.render.photons_per_pass << " photons, max_depth "
        << s.render.max_depth << ", alpha " << s.render.alpha << "\n"
        << "imports:    " << imported_triangles(s) << " imported triangles (" << emissive_triangles(s) << " emissive; "
        << (imported_instances(s) > 0 ? std::to_string(held_triangles(s)) + " held once, " +
                                            std::to_string(imported_instances(s)) + " placed copies; "
                                      : std::string())
        << format_bytes(imported_mesh_bytes(s)) << " of vertex data, about " << format_bytes(imported_bvh_bytes(s))
        << " more in the BVH); " << s.textures.size() << " texture" << (s.textures.size() == 1 ? "" : "s") << ", "
        << format_bytes(texture_bytes(s)) << "\n";
    if (const auto [all, blender3] = principled_counts(s); all > 0)
        out << "principled: " << all << " metallic-roughness material" << (all == 1 ? "" : "s") << ", " << blender3
            << " drawn as Blender 3.x's Cycles draws them (\"blender3\"), " << all - blender3
            << " energy-conserving\n";
    print_light_powers(out, s, f.size);
    for (const std::string& w : scene_warnings(ctx, f)) err << w << "\n";

    // Memory: the time buckets (what K divides) and the fixed part (what it does not); a
    // process needs about the sum. --max-memory bounds the sum, --max-bucket-memory the buckets.
    // info takes no -o: its figures are a render's with a video of the usual kind (.mp4, x264);
    // EXR or PNG frames alone need the encoder's line less, .mkv (FFV1) and .webm (VP9) more.
    RunOptions with_video = options;
    if (with_video.output.empty()) with_video.output = "out.mp4";
    const MemoryBaseline baseline = memory_baseline(s, with_video);
    const uint64_t fixed_part = baseline.total();
    out << "memory:     fixed overhead about " << format_bytes(fixed_part)
        << " (the parts below), plus the time buckets of the sections in flight;\n"
        << "            --max-memory bounds the sum (the whole process), --max-bucket-memory the buckets alone\n";
    for (const auto& [name, bytes] : baseline.terms()) {
        std::string left = "  " + std::string(name);
        left.resize(std::max<size_t>(left.size() + 1, 34), ' ');
        out << left << format_bytes(bytes);
        if (std::string_view(name).starts_with("photon map"))
            out << " (" << fixed(baseline.records_per_path, 2) << " records a photon path, from a pilot of the scene)";
        if (std::string_view(name) == "video encoder") out << " (x264, as for -o out.mp4)";
        out << "\n";
    }
    if (ranks > 1) out << "ranks:      " << ranks << " (MPI): each holds the buckets of 1/" << ranks << " of the pixels\n";
    out << "  sections K   buckets per section" << (ranks > 1 ? " per rank" : "         ") << " whole process" << (ranks > 1 ? " per rank" : "") << "\n";
    for (int k : {1, 2, 4, 8}) {
        if (k > s.time.frames) break;
        uint64_t b = section_buffer_bytes(s, k, ranks);
        std::string left = "  " + std::to_string(k) + std::string(k < 10 ? 12 : 11, ' ') + format_bytes(b) + " (" +
                           std::to_string(b) + " bytes)";
        left.resize(std::max<size_t>(left.size() + 1, 45), ' ');
        out << left << "about " << format_bytes(b + fixed_part) << "\n";
    }
    if (options.max_memory_bytes || options.max_bucket_bytes) {
        try {
            MemoryPlan plan = plan_memory(s, with_video, baseline);
            out << "  with " << (options.max_memory_bytes ? "--max-memory " + format_bytes(*options.max_memory_bytes)
                                                          : "--max-bucket-memory " + format_bytes(*options.max_bucket_bytes))
                << ": K = " << plan.sections << " (" << format_bytes(plan.buffer_bytes_per_section)
                << " of buckets per section, about " << format_bytes(plan.buffers_in_flight() + fixed_part)
                << " in all)\n";
        } catch (const InputError& e) {
            out << "  " << e.what() << "\n";
        }
        return;
    }
    out << "  --max-memory   smallest K\n";
    for (uint64_t mib : {256ull, 1024ull, 4096ull}) {
        RunOptions o;
        o.max_memory_bytes = mib << 20;
        o.ranks = ranks;
        std::string label = mib >= 1024 ? std::to_string(mib / 1024) + "G" : std::to_string(mib) + "M";
        out << "  " << label << std::string(15 - label.size(), ' ');
        try {
            out << plan_memory(s, o, baseline).sections << "\n";
        } catch (const InputError&) {
            out << "does not fit (needs at least " << format_bytes(fixed_part + section_buffer_bytes(s, s.time.frames, ranks))
                << ")\n";
        }
    }
}

nlohmann::json scene_info_json(const SceneDesc& s, const RunOptions& options) {
    using nlohmann::json;
    const int ranks = std::max(1, options.ranks);
    const Timeline tl = timeline_of(s);
    RenderContext ctx(s);
    const SceneFacts f = scene_facts(ctx);
    json j;
    j["scene"] = s.source;
    j["width"] = s.camera.width;
    j["height"] = s.camera.height;
    j["shapes"] = s.shapes.size();
    j["materials"] = s.materials.size();
    j["lights"] = s.lights.size();
    j["medium"] = s.medium.present;
    j["triangles"] = f.triangles;
    j["spheres"] = f.spheres;
    j["size_m"] = {f.size.x, f.size.y, f.size.z};
    j["meters_per_unit"] = s.meters_per_unit;
    j["diagonal_m"] = f.diagonal_m;
    j["crossing_ns"] = f.crossing_ns;
    j["time"] = {{"start_ns", s.time.start_ns}, {"end_ns", s.time.end_ns}, {"frames", s.time.frames},
                 {"frame_ns", tl.delta()}, {"frame_m", tl.delta() * kSpeedOfLight}, {"fps", s.time.fps}};
    j["first_arrival_ns"] = f.first_arrival_ns ? json(*f.first_arrival_ns) : json(nullptr);
    j["last_direct_arrival_ns"] = f.last_direct_arrival_ns ? json(*f.last_direct_arrival_ns) : json(nullptr);
    j["camera_tof"] = s.render.camera_tof;
    j["emission"] = s.emission.mode == EmissionMode::Constant ? "constant" : "pulse";
    j["render"] = {{"passes", s.render.passes}, {"photons_per_pass", s.render.photons_per_pass},
                   {"max_depth", s.render.max_depth}, {"alpha", s.render.alpha}, {"seed", s.render.seed}};
    j["imports"] = {{"triangles", imported_triangles(s)}, {"emissive_triangles", emissive_triangles(s)},
                    {"held_triangles", held_triangles(s)}, {"instances", imported_instances(s)},
                    {"mesh_bytes", imported_mesh_bytes(s)}, {"bvh_bytes", imported_bvh_bytes(s)},
                    {"textures", s.textures.size()}, {"texture_bytes", texture_bytes(s)}};
    const auto [mr_all, mr_blender3] = principled_counts(s);
    j["principled"] = {{"metallic_roughness", mr_all}, {"blender3", mr_blender3}};
    std::vector<const ShapeDesc*> from(s.lights.size(), nullptr);
    for (const ShapeDesc& sh : s.shapes)
        for (int i = sh.first_light; i < sh.first_light + sh.light_count; ++i) from[static_cast<size_t>(i)] = &sh;
    json powers = json::array();
    for (size_t i = 0; i < s.lights.size(); ++i) {
        const LightDesc& l = s.lights[i];
        json p = {{"type", light_type_name(l.type)}, {"watts", light_watts(l, f.size)}};
        if (l.type == LightType::Sun) p["irradiance_w_m2"] = (double(l.irradiance.x) + l.irradiance.y + l.irradiance.z) / 3;
        if (from[i]) p["from"] = from[i]->file;
        powers.push_back(p);
    }
    j["light_powers"] = powers;
    json emissive = json::array();
    for (size_t i = 0; i < s.shapes.size(); ++i)
        if (const double w = emissive_watts(s, s.shapes[i]); w > 0) {
            json e = {{"watts", w}};
            if (s.shapes[i].file.empty()) e["shape"] = i; else e["file"] = s.shapes[i].file;
            emissive.push_back(e);
        }
    j["emissive_surfaces"] = emissive;
    j["warnings"] = scene_warnings(ctx, f);

    RunOptions with_video = options;  // as print_scene_info: a render with an .mp4
    if (with_video.output.empty()) with_video.output = "out.mp4";
    const MemoryBaseline baseline = memory_baseline(s, with_video);
    json memory;
    memory["fixed_bytes"] = baseline.total();
    json terms = json::object();
    for (const auto& [name, bytes] : baseline.terms()) terms[name] = bytes;
    memory["fixed_terms"] = terms;
    memory["records_per_path"] = baseline.records_per_path;
    memory["ranks"] = ranks;
    json by_k = json::array();
    for (int k : {1, 2, 4, 8}) {
        if (k > s.time.frames) break;
        const uint64_t b = section_buffer_bytes(s, k, ranks);
        by_k.push_back({{"sections", k}, {"bucket_bytes", b}, {"whole_process_bytes", b + baseline.total()}});
    }
    memory["by_sections"] = by_k;
    if (options.max_memory_bytes || options.max_bucket_bytes) {
        try {
            const MemoryPlan plan = plan_memory(s, with_video, baseline);
            memory["planned"] = {{"sections", plan.sections}, {"bucket_bytes", plan.buffer_bytes_per_section},
                                 {"whole_process_bytes", plan.buffers_in_flight() + baseline.total()}};
        } catch (const InputError& e) {
            memory["planned"] = {{"error", e.what()}};
        }
    } else {
        json smallest = json::object();
        for (uint64_t mib : {256ull, 1024ull, 4096ull}) {
            RunOptions o;
            o.max_memory_bytes = mib << 20;
            o.ranks = ranks;
            const std::string label = mib >= 1024 ? std::to_string(mib / 1024) + "G" : std::to_string(mib) + "M";
            try {
                smallest[label] = plan_memory(s, o, baseline).sections;
            } catch (const InputError&) {
                smallest[label] = nullptr;  // does not fit
            }
        }
        memory["smallest_sections"] = smallest;
    }
    j["memory"] = memory;
    return j;
}

}  // namespace sl
