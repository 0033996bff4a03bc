#pragma once
// Which diffuse base a glTF file's own writer meant (config/scene_desc.h, PrincipledBase): a
// file written by Blender's exporter before Blender 4.0 was made from Principled v1 materials,
// whose diffuse base Cycles 3.x draws uncapped (Burley's shape), so that is what its author
// saw; any other writer (Blender 4.x: Principled v2, which conserves energy) gets the default.
// The scene entry's "principled" and --gltf-principled still decide over this.
#include <cstdlib>
#include <optional>
#include <string>

#include "config/scene_desc.h"

namespace sl {

// The exporter writes asset.generator as "Khronos glTF Blender I/O v<major>.<minor>.<patch>",
// its major the Blender release's (v1.x and v2.x: Blender 2.8x-2.9x; v3.x: Blender 3.x).
inline std::optional<PrincipledBase> principled_of_writer(const std::string& generator) {
    static const std::string kBlender = "Khronos glTF Blender I/O v";
    if (generator.rfind(kBlender, 0) != 0) return std::nullopt;
    const char* digits = generator.c_str() + kBlender.size();
    if (*digits < '0' || *digits > '9') return std::nullopt;
    const long major = std::strtol(digits, nullptr, 10);
    if (major <= 3) return PrincipledBase::Blender3;
    return std::nullopt;
}

}  // namespace sl
