#include "pipeline/run_stats.h"

#include <sys/resource.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "foundation/errors.h"
#include "stages/output/atomic_file.h"

namespace sl {

uint64_t peak_rss_bytes() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<uint64_t>(u.ru_maxrss) * 1024;  // Linux reports KiB
}

nlohmann::json stats_json(const RunSummary& s) {
    const PipelineStats& p = s.pipeline;
    const SceneDesc& sc = *s.scene;
    nlohmann::json j;
    j["frames"] = sc.time.frames;
    j["sections"] = s.plan.sections;
    j["sections_done"] = p.sections_done;
    j["passes"] = sc.render.passes;
    j["photons_per_pass"] = sc.render.photons_per_pass;
    j["width"] = sc.camera.width;
    j["height"] = sc.camera.height;
    j["strategy"] = strategy_name(s.strategy);
    j["threads"] = s.threads;
    j["wall_seconds"] = s.wall_seconds;
    j["stage_seconds"] = {
        {"setup", s.setup_seconds},
        {"section_buffers", p.buffers},
        {"exposure_preview", p.exposure_pass},
        {"camera_paths", p.render.camera_paths},
        {"photon_passes", p.render.photons},
        {"time_bucket_scatter", p.render.gather},
        {"beam_estimate", p.render.volume},  // part of the camera pass, with a medium only
        {"frame_assembly", p.assembly},
        {"writers", p.writing + s.output_seconds},
    };
    j["photons_traced"] = p.photons;
    j["photon_records"] = p.photon_records;
    j["rays_traced"] = p.rays;
    j["peak_rss_bytes"] = peak_rss_bytes();
    j["buffer_bytes_per_section"] = s.plan.buffer_bytes_per_section;
    j["fixed_overhead_bytes"] = s.plan.fixed_overhead_bytes;
    j["photon_map_bytes"] = p.photon_map_bytes;
    j["sections_overlap"] = s.plan.overlap;
    j["exposure"] = s.exposure;
    j["interrupted"] = p.interrupted;
    j["ranks"] = p.ranks;
    if (p.ranks > 1)  // rank 0's payload: what it received with the passes and with the frames
        j["exchanged_bytes"] = {{"passes_received", p.exchanged_received[0]},
                                {"passes_sent", p.exchanged_sent[0]},
                                {"passes", p.passes_run},
                                {"frames_received", p.exchanged_received[1]},
                                {"photon_grid_seconds", p.render.grid},  // rank 0's, part of photon_passes
                                {"photon_transfer_seconds", p.photon_transfer_seconds}};
    // The passes each section's frames got (0: not written); with --time-limit or after an
    // interrupt they can be fewer than "passes".
    j["passes_per_section"] = p.passes_per_section;
    int reached = 0;
    for (int n : p.passes_per_section)
        if (n > 0) reached = reached == 0 ? n : std::min(reached, n);
    j["passes_reached"] = reached;
    if (p.interrupted_section >= 0) j["interrupted_section"] = p.interrupted_section;
    if (s.time_limit > 0) j["time_limit_seconds"] = s.time_limit;
    if (!s.checkpoint_dir.empty())
        j["checkpoints"] = {{"dir", s.checkpoint_dir},
                            {"writes", s.checkpoint_writes},
                            {"bytes_each", s.checkpoint_bytes},
                            {"seconds_total", s.checkpoint_seconds},
                            {"seconds_longest", s.checkpoint_longest}};
    if (s.preview_writes > 0) j["preview_writes"] = s.preview_writes;
    return j;
}

void write_stats_json(const std::string& path, const RunSummary& s) {
    const nlohmann::json j = stats_json(s);
    // A device or FIFO (/dev/stdout, a pipe) is written in place, a link through to its target
    // (atomic_file.h): never replaced by a rename.
    const std::string target = temp_sibling(path);
    {
        std::ofstream f(target);
        f << j.dump(2) << "\n";
        f.flush();
        if (!f) {
            discard_file(target);
            throw RuntimeFailure("--stats " + path + ": cannot write");
        }
    }
    commit_file(target, path);
}

}  // namespace sl
