#pragma once
// A fingerprint of everything that decides a frame's pixels: the scene (mesh files' bytes
// included), the render settings, the section count and the strategy. Stored in every EXR so
// that --resume never mixes frames of different renders.
#include <string>

#include "config/run_options.h"
#include "config/scene_desc.h"

namespace sl {

std::string settings_fingerprint(const SceneDesc& scene, int sections, Strategy strategy);

}  // namespace sl
