#pragma once
// `slowlight render model.glb` (or .gltf, .obj) without a scene file: a scene made from the
// model alone. Camera: the file's first camera, or one in front of the scene (looking along
// -z, y up, as glTF's axes are) that frames its bounds. Lights: the file's (its emissive
// materials and KHR_lights_punctual lights). Time: 0 to the time light needs to cross the
// scene's bounding-box diagonal three times. Everything else: the scene file's defaults, and
// the command line's flags override as usual.
#include <optional>
#include <string>

#include "config/scene_desc.h"
#include "core/import/resolve_imports.h"  // ImportBudget

namespace sl {

// True for a path whose extension is .glb, .gltf or .obj (any case).
bool is_model_file(const std::string& path);

// Throws InputError naming the file when it cannot be read or has no light. `light_units`: how a
// glTF file's lights are read (--gltf-light-units; empty: photometric); `principled`: how its
// metallic-roughness materials draw their diffuse base (--gltf-principled; empty: energy-conserving).
SceneDesc scene_for_model(const std::string& path, std::optional<LightUnits> light_units = {},
                          const ImportBudget& budget = {}, std::optional<PrincipledBase> principled = {});

}  // namespace sl
