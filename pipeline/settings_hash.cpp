#include "pipeline/settings_hash.h"

#include <cstdint>
#include <cstdio>
#include <sstream>

#include "config/input_file.h"

namespace sl {
namespace {

constexpr uint64_t kMaxMeshBytes = uint64_t(1) << 30;  // as the mesh loader allows

struct Fnv1a {
    uint64_t h = 1469598103934665603ull;
    void bytes(const void* data, size_t n) {
        auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
    }
};

std::ostream& operator<<(std::ostream& o, Vec3 v) { return o << v.x << ',' << v.y << ',' << v.z; }

}  // namespace

std::string settings_fingerprint(const SceneDesc& s, int sections, Strategy strategy) {
    std::ostringstream t;
    t.precision(17);
    const CameraDesc& c = s.camera;
    t << "camera " << c.position << ' ' << c.look_at << ' ' << c.up << ' ' << c.vfov_deg << ' ' << c.width << 'x' << c.height << '\n';
    for (const MaterialDesc& m : s.materials)
        t << "material " << static_cast<int>(m.type) << ' ' << m.albedo << ' ' << m.reflectance << ' ' << m.ior << '\n';
    Fnv1a meshes;
    for (const ShapeDesc& sh : s.shapes) {
        t << "shape " << static_cast<int>(sh.type) << ' ' << sh.material << ' ' << sh.corner << ' ' << sh.edge1 << ' '
          << sh.edge2 << ' ' << sh.min << ' ' << sh.max << ' ' << sh.center << ' ' << sh.radius << ' ' << sh.translate
          << ' ' << sh.scale << ' ' << sh.rotate_deg << '\n';
        if (sh.type == ShapeType::Mesh && !s.imports_resolved) {
            // Never blindly: a mesh swapped for a FIFO or /dev/zero must not hang the run.
            read_input_chunks(sh.file, kMaxMeshBytes, s.source + ": mesh '" + sh.file + "'", "mesh file",
                              [&](const char* p, size_t n) { meshes.bytes(p, n); });
        }
    }
    for (const std::string& file : s.input_files)  // the scene, imported meshes, libraries, buffers, textures
        read_input_chunks(file, uint64_t(4) << 30, s.source + ": '" + file + "'", "input file",
                          [&](const char* p, size_t n) { meshes.bytes(p, n); });
    for (const LightDesc& l : s.lights) {
        t << "light " << static_cast<int>(l.type) << ' ' << l.position << ' ' << l.corner << ' ' << l.edge1 << ' ' << l.edge2
          << ' ' << l.direction << ' ' << l.power << ' ' << l.radiance << ' ' << l.cone_deg << ' ' << l.radius;
        if (l.type == LightType::Sun) t << " sun " << l.irradiance << ' ' << l.angle_deg;  // others: as before
        t << '\n';
    }
    const MediumDesc& m = s.medium;
    t << "medium " << m.present << ' ' << m.sigma_a << ' ' << m.sigma_s << ' ' << m.g << ' ' << m.has_bounds << ' '
      << m.bounds_min << ' ' << m.bounds_max << '\n';
    t << "time " << s.time.start_ns << ' ' << s.time.end_ns << ' ' << s.time.frames << '\n';
    t << "emission " << static_cast<int>(s.emission.mode) << ' ' << s.emission.width_frames << '\n';
    const RenderDesc& r = s.render;
    t << "render " << r.passes << ' ' << r.photons_per_pass << ' ' << r.max_depth << ' ' << r.radius << ' ' << r.alpha
      << ' ' << r.camera_tof << ' ' << r.seed << ' ' << r.ambient << '\n';
    t << "sections " << sections << " strategy " << static_cast<int>(strategy) << " meshes " << meshes.h << '\n';
    Fnv1a h;
    std::string text = t.str();
    h.bytes(text.data(), text.size());
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h.h));
    return hex;
}

}  // namespace sl
