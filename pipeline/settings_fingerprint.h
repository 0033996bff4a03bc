#pragma once
// A fingerprint of everything that decides a frame's pixels: the scene (mesh files' bytes
// included), the render settings, the section count and the strategy, made from a canonical
// serialization of all the settings so that a new field cannot be left out by hand. Stored in every EXR so
// that --resume never mixes frames of different renders.
#include <string>

#include "config/run_options.h"
#include "config/scene_desc.h"

namespace sl {

// 16 hex digits: XXH64 of canonical_settings and the bytes of every input file.
std::string settings_fingerprint(const SceneDesc& scene, int sections, Strategy strategy);

// The settings as canonical JSON: every field of the scene's structs (config/scene_fields.h)
// except a short list that decides no pixel (file paths, whose bytes are hashed instead; the
// video's fps), with the section count and the strategy.
std::string canonical_settings(const SceneDesc& scene, int sections, Strategy strategy);

}  // namespace sl
