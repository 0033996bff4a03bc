#pragma once
// `slowlight info SCENE.json`: what the scene holds, its size and when its light arrives, and
// what a render costs in memory by K (the whole process and the time buckets). Warnings about
// the scene go to `err`.
#include <ostream>

#include "config/run_options.h"
#include "config/scene_desc.h"

namespace sl {
void print_scene_info(std::ostream& out, std::ostream& err, const SceneDesc& scene, const RunOptions& options);
}  // namespace sl
