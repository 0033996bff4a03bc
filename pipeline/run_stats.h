#pragma once
// --stats FILE.json: machine-readable numbers about a run (times, photons, memory, exposure).
#include <nlohmann/json.hpp>
#include <string>

#include "pipeline/memory_plan.h"
#include "pipeline/render_pipeline.h"

namespace sl {

struct RunSummary {
    const SceneDesc* scene = nullptr;
    MemoryPlan plan;
    PipelineStats pipeline;
    double wall_seconds = 0, setup_seconds = 0, output_seconds = 0;
    double exposure = 1;
    Strategy strategy = Strategy::Single;
    int threads = 0;
    double time_limit = 0;  // seconds; 0: none
    std::string checkpoint_dir;
    int checkpoint_writes = 0, preview_writes = 0;
    uint64_t checkpoint_bytes = 0;  // of one checkpoint
    double checkpoint_seconds = 0, checkpoint_longest = 0;
};

uint64_t peak_rss_bytes();
// The --stats file's numbers (the Python module returns the same ones).
nlohmann::json stats_json(const RunSummary& s);
void write_stats_json(const std::string& path, const RunSummary& s);

}  // namespace sl
