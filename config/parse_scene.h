#pragma once
// Reading and validating scene files (format: docs/scene-format.md). Everything is checked up
// front; any problem throws InputError with one line
//   `<file>: key '<dotted.key.path>': <what is wrong>`   or   `<file>: line L, column C: ...`
// (the caller prefixes "error: "). The result is in meters, nanoseconds and per-meter units.
#include <string>

#include "config/overrides.h"  // apply_overrides: most callers parse, then override
#include "config/scene_desc.h"

namespace sl {

// Reads and parses a scene file. Mesh paths are resolved against the file's folder.
SceneDesc parse_scene_file(const std::string& path);

// Parses scene JSON. `source_name` names the text in messages; `base_dir` resolves mesh paths
// ("" means the current directory).
SceneDesc parse_scene_text(const std::string& text, const std::string& source_name,
                           const std::string& base_dir);

// The built-in demo scene (samples/cornell_box.json compiled in), source "<default>".
SceneDesc parse_default_scene();

}  // namespace sl
