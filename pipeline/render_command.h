#pragma once
// `slowlight render`: from the parsed command line to the exit status, as a short sequence of
// named steps (render_command.cpp); `load_scene`, the one place a run reads its scene and the
// files it imports.
#include <string>
#include <vector>

#include "config/run_options.h"
#include "config/scene_desc.h"
#include "pipeline/memory_plan.h"
#include "stages/render/rank_exchange.h"

namespace sl {

// The scene of the command line (the built-in demo, a model file or a scene file), with every
// imported file read, then the command line's overrides. Each file is read here, once.
SceneDesc load_scene(const RunOptions& o);
// load_scene's steps after parsing: the glTF light units and diffuse base, every imported file read, then the
// command line's overrides (for a scene parsed elsewhere, such as the Python module's dicts).
void complete_scene(SceneDesc& scene, const RunOptions& o);

// InputError when the plan needs more memory than the machine has (refused up front: it could
// only end in running out of memory).
void check_fits_machine(const MemoryPlan& plan);

// Under an MPI launcher: this process's exchange with the other ranks (null: one process) and
// whether rendering one section while rank 0 writes another may use both channels at once.
struct RankSetup {
    RankExchange* ex = nullptr;
    bool concurrent_channels = false;
};

// Returns the exit status: 0, or 130 when interrupted (failures throw InputError/RuntimeFailure).
int render_command(RunOptions o, const std::vector<std::string>& argv, const RankSetup& ranks);

}  // namespace sl
