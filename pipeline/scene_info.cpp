#include "pipeline/scene_info.h"

#include "core/errors.h"
#include "core/import/resolve_imports.h"
#include "pipeline/memory_plan.h"

namespace sl {

void print_scene_info(std::ostream& out, const SceneDesc& s) {
    const double delta = (s.time.end_ns - s.time.start_ns) / s.time.frames;
    out << "scene:      " << s.source << "\n"
        << "image:      " << s.camera.width << " x " << s.camera.height << "\n"
        << "shapes:     " << s.shapes.size() << ", materials: " << s.materials.size()
        << ", lights: " << s.lights.size() << (s.medium.present ? ", with a medium" : ", vacuum") << "\n"
        << "time:       " << s.time.start_ns << " to " << s.time.end_ns << " ns, " << s.time.frames
        << " frames of " << delta << " ns (" << delta * 0.299792458 << " m of light), " << s.time.fps << " fps\n"
        << "emission:   " << (s.emission.mode == EmissionMode::Constant ? "constant" : "pulse") << "\n"
        << "render:     " << s.render.passes << " passes x " << s.render.photons_per_pass << " photons, max_depth "
        << s.render.max_depth << ", alpha " << s.render.alpha << "\n"
        << "geometry:   " << imported_triangles(s) << " imported triangles (" << emissive_triangles(s) << " emissive; " << format_bytes(imported_mesh_bytes(s))
        << " of vertex data, about " << format_bytes(imported_bvh_bytes(s)) << " more in the BVH); " << s.textures.size()
        << " texture" << (s.textures.size() == 1 ? "" : "s") << ", " << format_bytes(texture_bytes(s)) << "\n"
        << "memory:     fixed overhead about " << format_bytes(fixed_overhead_bytes(s)) << "\n";
    out << "  sections K   buffers per section\n";
    for (int k : {1, 2, 4, 8}) {
        if (k > s.time.frames) break;
        uint64_t b = section_buffer_bytes(s, k);
        out << "  " << k << (k < 10 ? "            " : "           ") << format_bytes(b) << " (" << b << " bytes)\n";
    }
    out << "  budget       smallest K (--max-memory)\n";
    for (uint64_t mib : {64ull, 256ull, 1024ull, 4096ull}) {
        RunOptions o;
        o.max_memory_bytes = mib << 20;
        std::string label = mib >= 1024 ? std::to_string(mib / 1024) + "G" : std::to_string(mib) + "M";
        out << "  " << label << std::string(13 - label.size(), ' ');
        try {
            out << plan_memory(s, o).sections << "\n";
        } catch (const InputError&) {
            out << "does not fit (one frame per section needs " << format_bytes(section_buffer_bytes(s, s.time.frames)) << ")\n";
        }
    }
}

}  // namespace sl
