#include "pipeline/memory_plan.h"

#include "core/import/resolve_imports.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <unistd.h>

#include "foundation/errors.h"
#include "stages/render/photon_map.h"
#include "stages/render/section_buffer.h"
#include "stages/render/section_layout.h"

namespace sl {

static uint64_t current_rss_bytes() {
    std::ifstream statm("/proc/self/statm");
    uint64_t size = 0, resident = 0;
    statm >> size >> resident;
    return resident * static_cast<uint64_t>(sysconf(_SC_PAGESIZE));
}

static size_t pixel_count(const SceneDesc& s) {
    return static_cast<size_t>(s.camera.width) * static_cast<size_t>(s.camera.height);
}

uint64_t section_buffer_bytes(const SceneDesc& scene, int sections, int ranks) {
    const Timeline tl = timeline_of(scene);
    const int slots = max_section_slots(tl, scene.emission.mode, sections);
    const size_t pixels = PixelShare{0, std::max(1, ranks), pixel_count(scene)}.count();  // rank 0 has the most
    return SectionBuffer::bytes_needed(pixels, slots, !is_black(scene.render.ambient));
}

uint64_t fixed_overhead_bytes(const SceneDesc& scene) {
    uint64_t pixels = pixel_count(scene);
    // Photon map: a closed white room stores about albedo/(1-albedo) ~ 2.5 records per path;
    // budget 4 (or max_depth - 1) records, each in a batch and sorted, with its staged slot
    // (and, per thread, a copy of the 64th of them being sorted; budgeted as 4 bytes a record),
    // plus a hash table of twice the records.
    uint64_t per_path = static_cast<uint64_t>(std::clamp(scene.render.max_depth - 1, 1, 4));
    uint64_t records = static_cast<uint64_t>(scene.render.photons_per_pass) * per_path;
    uint64_t photons = records * (2 * sizeof(PhotonRecord) + 2 * 4) + 4 * records * 2 * 4;
    // Frames on their way out: a running sum (double), three float frames, an 8-bit frame, a
    // second frame in the codec's format (one is converted while the other is encoded), and
    // the encoder's own look-ahead (x264 keeps some tens of frames in 4:2:0); and the float
    // frame a section carries over to the next (constant light).
    uint64_t frames = pixels * (3 * 8 + 4 * 3 * 4 + 2 * 3);
    // A medium (with some extinction): volume photons, budgeted like surface records (up to 4
    // events a path), each in its batch, concatenated, in leaf order (position + payload), with
    // its BVH index and a node per 4.
    uint64_t volume = 0;
    const MediumDesc& m = scene.medium;
    if (m.present && max_component(m.sigma_a + m.sigma_s) > 0) {
        uint64_t events = static_cast<uint64_t>(scene.render.photons_per_pass) *
                          static_cast<uint64_t>(std::clamp(scene.render.max_depth, 1, 4));
        volume = events * (2 * sizeof(VolumePhoton) + 4 + 3 * 4 + 40 + 32 / 4);
    }
    // The encoder, whichever the container asks for: measured at 512x512 with four sections
    // against EXR-only output, x264 ~100 bytes per pixel, VP9 ~170, FFV1 ~190 (frames on their
    // way out included); 260 covers them all. And the process as it stands (libraries, the
    // scene's BVH): measured, not guessed.
    uint64_t encoder = pixels * 260;
    // Imported meshes and textures: their arrays, and Embree's copy and BVH.
    encoder += imported_mesh_bytes(scene) + imported_bvh_bytes(scene) + texture_bytes(scene);
    return photons + frames + volume + encoder + current_rss_bytes() + (16ull << 20);
}

MemoryPlan plan_memory(const SceneDesc& scene, const RunOptions& options) {
    MemoryPlan plan;
    plan.fixed_overhead_bytes = fixed_overhead_bytes(scene);
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

std::string format_bytes(uint64_t bytes) {
    char buf[64];
    double b = static_cast<double>(bytes);
    if (b >= 1024.0 * 1024 * 1024) std::snprintf(buf, sizeof buf, "%.2f GiB", b / (1024.0 * 1024 * 1024));
    else if (b >= 1024.0 * 1024) std::snprintf(buf, sizeof buf, "%.1f MiB", b / (1024.0 * 1024));
    else if (b >= 1024.0) std::snprintf(buf, sizeof buf, "%.1f KiB", b / 1024.0);
    else std::snprintf(buf, sizeof buf, "%llu B", static_cast<unsigned long long>(bytes));
    return buf;
}

}  // namespace sl
