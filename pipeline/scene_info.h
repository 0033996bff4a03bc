#pragma once
// `slowlight info SCENE.json`: what the scene holds and what it costs in memory by K.
#include <ostream>

#include "config/scene_desc.h"

namespace sl {
// `ranks`: the memory is per rank when that many MPI ranks share the render.
void print_scene_info(std::ostream& out, const SceneDesc& scene, int ranks = 1);
}  // namespace sl
