#pragma once
// `slowlight info SCENE.json`: what the scene holds and what it costs in memory by K.
#include <ostream>

#include "config/scene_desc.h"

namespace sl {
void print_scene_info(std::ostream& out, const SceneDesc& scene);
}  // namespace sl
