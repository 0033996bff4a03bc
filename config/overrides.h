#pragma once
// The command line's render overrides (--frames, --passes, --width, --emission, ...) applied to
// a parsed scene, re-validating what they affect; apart from the scene file's parser because
// they come from another source and report against flags, not keys.
#include <optional>
#include <string>
#include <string_view>

#include "config/run_options.h"
#include "config/scene_desc.h"

namespace sl {

// Applies command-line overrides and re-validates what they affect. Bad values throw
// InputError "command line: --frames: ...".
void apply_overrides(SceneDesc& scene, const RenderOverrides& o);

// --gltf-light-units: the units of every gltf shape that does not name its own "light_units".
// Before resolve_imports, which reads the files.
void apply_gltf_light_units(SceneDesc& scene, std::optional<LightUnits> units);

// --gltf-principled: the diffuse base of every gltf shape that does not name its own
// "principled" (nor a "material" of the scene's). Before resolve_imports.
void apply_gltf_principled(SceneDesc& scene, std::optional<PrincipledBase> principled);

// Parses an --emission value: "constant", "pulse" or "pulse:WIDTH_NS" (width_frames is left
// for apply_overrides to check against the frame width). Throws "command line: --emission: ...".
EmissionDesc parse_emission_option(const std::string& spec);

// Throws InputError "command line: FLAG: WHAT".
[[noreturn]] void command_line_error(std::string_view flag, const std::string& what);

}  // namespace sl
