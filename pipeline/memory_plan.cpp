#include "pipeline/memory_plan.h"

#include "core/emissive_triangles.h"

#include "core/import/resolve_imports.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "foundation/errors.h"
#include "stages/render/edge_radius.h"
#include "stages/render/photon_map.h"
#include "stages/render/render_context.h"
#include "stages/render/section_buffer.h"
#include "stages/render/section_layout.h"
#include "stages/render/beam_splat.h"
#include "stages/render/volume_photon_map.h"

namespace sl {

namespace {

constexpr uint64_t kMiB = 1ull << 20;

// The program itself: code, libraries (FFmpeg's alone map ~200 of them), TBB's and Embree's
// start-up, the scene's parse. Measured once as the peak RSS (--stats peak_rss_bytes) of a render
// that holds next to nothing else, 33.2-33.3 MiB in four runs on the development machine
// (Debian 12, FFmpeg 5.1, Release build, 2026-12-03):
//   slowlight render samples/cornell_box.json --frames 2 --width 16 --height 16 --passes 1
//       --photons 100 --no-progress --exr-dir DIR --stats S.json
// A constant on purpose: what the process happens to have mapped when it plans must not move K.
constexpr uint64_t kProgramBytes = 34 * kMiB;

size_t pixel_count(const SceneDesc& s) {
    return static_cast<size_t>(s.camera.width) * static_cast<size_t>(s.camera.height);
}

// The video encoder the output's container selects (the table in stages/output/video_encoder.cpp)
// and what it costs beyond our own frames. The codec's state is the library's, not a type of
// ours, so it is measured: the peak RSS of renders at 8 frames of 256², 512² and 768² (1000
// photons, 2 passes) into each container, less the same render with --exr-dir only and less the
// staged frames below; a straight line through the three sizes (slope: bytes per pixel,
// intercept: the library's state at open). 2026-12-03, same machine as kProgramBytes.
struct Codec {
    const char* name;
    uint64_t fixed;         // the codec's state at open (and its pages of code first touched)
    uint64_t per_pixel;     // its own pictures: look-ahead, references, slice contexts
    bool full_chroma;       // 4:4:4 (else 4:2:0) in our two staged frames
};
constexpr Codec kX264{"x264", 7 * kMiB, 22, false};  // 5-frame look-ahead, 3 B-frames, 1 thread (20 fitted; 22: at 512² K = 8 the fit left no room)
constexpr Codec kFfv1{"FFV1", 4 * kMiB, 153, true};  // per-slice sample buffers, 4:4:4
constexpr Codec kVp9{"VP9", 23 * kMiB, 115, false};  // libvpx's lag of 25 frames, row-mt
constexpr Codec kY4m{"y4m", 0, 0, false};            // frames pass through as they are

const Codec* codec_for(const std::string& output) {
    if (output.empty()) return nullptr;
    if (output == "-") return &kY4m;
    std::string ext = std::filesystem::path(output).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".mp4" || ext == ".mov") return &kX264;
    if (ext == ".webm") return &kVp9;
    return &kFfv1;  // .mkv, and a device or FIFO without an extension (Matroska)
}

// Stored surface records and medium events per photon path: one pilot pass of the scene's own
// lights, full paths, a fixed seed and pass number, so the same scene always gives the same
// count (batches have their own random streams: the thread count does not matter either).
constexpr int64_t kPilotPhotons = 4 * PhotonMap::kBatch;

PilotYield scene_pilot_yield(const SceneDesc& scene) {
    if (scene.render.photons_per_pass <= 0) return {};
    return pilot_yield(RenderContext(scene), kPilotPhotons);
}

}  // namespace

uint64_t section_buffer_bytes(const SceneDesc& scene, int sections, int ranks) {
    const Timeline tl = timeline_of(scene);
    const int slots = max_section_slots(tl, scene.emission.mode, sections);
    const size_t pixels = PixelShare{0, std::max(1, ranks), pixel_count(scene)}.count();  // rank 0 has the most
    return SectionBuffer::bytes_needed(pixels, slots, !is_black(scene.render.ambient));
}

std::vector<std::pair<const char*, uint64_t>> MemoryBaseline::terms() const {
    return {{"program and libraries", program}, {"scene (meshes, BVH, textures, emitters)", scene},
            {"photon map (one pass)", photon_map}, {"volume photons (one pass)", volume_photons},
            {"frames on their way out", frames},  {"video encoder", encoder},
            {"gather radii, edge cuts and stars", gather_radii}};
}

MemoryBaseline memory_baseline(const SceneDesc& scene, const RunOptions& options) {
    MemoryBaseline b;
    const uint64_t pixels = pixel_count(scene);
    b.program = kProgramBytes;
    // Imported meshes and textures: their arrays, and Embree's copy and BVH (a fixed figure per
    // triangle, core/import/resolve_imports.cpp). The built-in shapes are a few hundred bytes.
    // The emitters' table holds every placed emissive triangle in scene space: a mesh placed
    // N times by instances costs its emissive triangles N times there.
    b.scene = imported_mesh_bytes(scene) + imported_bvh_bytes(scene) + texture_bytes(scene) +
              emissive_triangles(scene) * EmissiveTriangles::bytes_per_triangle();

    // One pass's photons: the pilot's records per path, 2% more for the pilot's own spread
    // (about 1% for 4096 paths), times this run's photons per pass.
    const auto [records_per_path, events_per_path] = scene_pilot_yield(scene);
    b.records_per_path = records_per_path;
    b.volume_events_per_path = events_per_path;
    const double photons = static_cast<double>(std::max<int64_t>(scene.render.photons_per_pass, 0));
    const auto count = [&](double per_path) { return static_cast<uint64_t>(std::ceil(photons * per_path * 1.02)); };
    b.photon_map = PhotonMap::bytes_needed(count(records_per_path));
    // The volume photons' tree, and their places on the image for the segments from the camera.
    if (events_per_path > 0)
        b.volume_photons =
            VolumePhotonMap::bytes_needed(count(events_per_path)) + BeamSplat::bytes_needed(count(events_per_path));

    // The automatic radius stops short of edges pixel by pixel: a float a pixel, for the run,
    // and where a pixel's disc is cut at an edge's line or kept in a star instead, an index a
    // pixel for each and the cut or star (edge_radius.h), and the plane each pixel's centre sees
    // (a neighbour's disc for points across a silhouette). How many pixels lie beside an edge is
    // known only once the map is made: a quarter of them is counted, as stars, the larger (the
    // samples: 20 % in the cathedral, fewer in the boxes).
    if (!(scene.render.radius > 0))
        b.gather_radii = pixels * (sizeof(float) + 2 * sizeof(uint32_t) + sizeof(GatherRadii::SeenPlane)) +
                         pixels / 4 * std::max(sizeof(EdgeCut), sizeof(EdgeStar));

    // Frames on their way out, per pixel: the running sum of constant light (FrameAssembler,
    // doubles), the float frames alive at once (the two the pipeline's frames_alive limiter lets
    // through, and the slot sum being assembled), the frame a section carries to the next
    // (constant light), and the 8-bit frame the tone mapping writes for a video or PNGs.
    using Channel = float;
    const uint64_t rgb_float = 3 * sizeof(Channel);
    uint64_t per_pixel = 3 * sizeof(double) + 3 * rgb_float + rgb_float;
    const bool eight_bit = !options.output.empty() || !options.png_dir.empty();
    if (eight_bit) per_pixel += 3 * sizeof(uint8_t);
    // The sensor images' sums (stages/output/sensor_images.h): two doubles per value and
    // frequency, one for the gate, a float for the first arrival.
    const SensorRequest& sensors = options.sensors;
    per_pixel += 3 * (2 * sizeof(double) * sensors.phasor_hz.size() + (sensors.gate_start_ns ? sizeof(double) : 0) +
                      (sensors.first_arrival ? sizeof(float) : 0));
    b.frames = pixels * per_pixel;
    // mitransient's order: up to 64 MiB of bins kept for the transpose (NpyTimeInnerWriter).
    if (!options.cube_path.empty() && options.cube_layout == CubeLayout::Mitransient) {
        const uint64_t plane = pixels * rgb_float, times = static_cast<uint64_t>(std::max(1, scene.time.frames));
        b.frames += plane * std::clamp<uint64_t>((uint64_t(64) << 20) / std::max<uint64_t>(plane, 1), 1, times);
    }

    // The encoder: the codec's own state and pictures, and our two staged frames in its pixel
    // format (one converted while the other is encoded).
    if (const Codec* c = codec_for(options.output)) {
        const uint64_t staged = 2 * (c->full_chroma ? 3 * sizeof(uint8_t) * pixels : 3 * sizeof(uint8_t) * pixels / 2);
        b.encoder = c->fixed + c->per_pixel * pixels + staged;
    }
    return b;
}

MemoryPlan plan_memory(const SceneDesc& scene, const RunOptions& options) {
    return plan_memory(scene, options, memory_baseline(scene, options));
}

MemoryPlan plan_memory(const SceneDesc& scene, const RunOptions& options, const MemoryBaseline& fixed) {
    MemoryPlan plan;
    plan.fixed = fixed;
    plan.fixed_overhead_bytes = fixed.total();
    const int frames = scene.time.frames;
    const int ranks = std::max(1, options.ranks);
    if (options.strategy == Strategy::FrameByFrame) {
        plan.sections = frames;
    } else if (options.sections) {
        if (*options.sections < 1 || *options.sections > frames)
            throw InputError("command line: --sections: must be between 1 and the number of frames (" +
                             std::to_string(frames) + "), got " + std::to_string(*options.sections));
        plan.sections = *options.sections;
    } else if (options.max_memory_bytes || options.max_bucket_bytes) {
        // --max-memory bounds the whole process: what is left after the fixed part is the
        // buckets' share. --max-bucket-memory bounds the buckets alone.
        const uint64_t one_frame = section_buffer_bytes(scene, frames, ranks);
        uint64_t budget = options.max_bucket_bytes.value_or(UINT64_MAX);
        if (options.max_memory_bytes) {
            const uint64_t whole = *options.max_memory_bytes;
            if (whole < plan.fixed_overhead_bytes + one_frame)
                throw InputError("command line: --max-memory: " + format_bytes(whole) +
                                 " cannot hold the process: its fixed part (libraries, scene, photon map, encoder) "
                                 "is about " + format_bytes(plan.fixed_overhead_bytes) +
                                 " and one frame per section needs " + format_bytes(one_frame) +
                                 " of time buckets; give at least " +
                                 std::to_string((plan.fixed_overhead_bytes + one_frame + (1u << 20) - 1) >> 20) +
                                 " MiB");
            budget = std::min(budget, whole - plan.fixed_overhead_bytes);
        }
        if (one_frame > budget)
            throw InputError("command line: --max-bucket-memory: " + format_bytes(budget) +
                             " cannot hold even one frame per section; that needs " + std::to_string(one_frame) +
                             " bytes of buffers, plus about " + format_bytes(plan.fixed_overhead_bytes) + " fixed");
        // The smallest K that fits (a section's buffer never grows with K: bisect).
        int lo = 1, hi = frames;
        while (lo < hi) {
            int mid = lo + (hi - lo) / 2;
            if (section_buffer_bytes(scene, mid, ranks) <= budget) hi = mid;
            else lo = mid + 1;
        }
        plan.sections = lo;
        plan.bucket_budget = budget;
    }
    plan.buffer_bytes_per_section = section_buffer_bytes(scene, plan.sections, ranks);
    // Encoding one section while the next renders needs two sections' buffers: only when a
    // budget says both fit (sections were asked for to save memory, so never by default).
    plan.overlap = plan.sections > 1 && plan.bucket_budget && 2 * plan.buffer_bytes_per_section <= plan.bucket_budget;
    return plan;
}

}  // namespace sl
