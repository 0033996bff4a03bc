#pragma once
// `slowlight info SCENE.json`: what the scene holds, its size and when its light arrives, and
// what a render costs in memory by K (the whole process and the time buckets). Warnings about
// the scene go to `err`.
#include <nlohmann/json.hpp>
#include <ostream>

#include "config/run_options.h"
#include "config/scene_desc.h"

namespace sl {
void print_scene_info(std::ostream& out, std::ostream& err, const SceneDesc& scene, const RunOptions& options);
// The same figures as numbers (bytes, ns, m, W), and the warnings as lines: the Python
// module's slowlight.info().
nlohmann::json scene_info_json(const SceneDesc& scene, const RunOptions& options);
}  // namespace sl
