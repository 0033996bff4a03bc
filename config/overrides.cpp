#include "config/overrides.h"

#include <cmath>

#include "config/limits.h"
#include "config/pulse_width.h"
#include "config/text_util.h"
#include "foundation/errors.h"

namespace sl {
namespace {

template <class T>
T in_range(std::string_view flag, T v, T lo, T hi) {
    if (v < lo || v > hi)
        command_line_error(flag, "must be an integer in " + std::to_string(lo) + ".." +
                                     std::to_string(hi) + ", got " + std::to_string(v));
    return v;
}

}  // namespace

void command_line_error(std::string_view flag, const std::string& what) {
    throw InputError("command line: " + std::string(flag) + ": " + what);
}

EmissionDesc parse_emission_option(const std::string& spec) {
    EmissionDesc e;
    if (spec == "constant") return e;
    e.mode = EmissionMode::Pulse;
    if (spec == "pulse") return e;
    const std::string prefix = "pulse:";
    if (spec.rfind(prefix, 0) != 0)
        command_line_error("--emission", "must be constant, pulse or pulse:WIDTH_NS, got '" +
                                             printable(spec) + "'");
    std::optional<double> w = parse_whole<double>(std::string_view(spec).substr(prefix.size()));
    if (!w || !std::isfinite(*w) || !(*w > 0))
        command_line_error("--emission",
                           "the pulse width must be a finite number of ns > 0, got '" +
                               printable(spec.substr(prefix.size())) + "'");
    e.width_ns = *w;
    return e;
}

void apply_overrides(SceneDesc& scene, const RenderOverrides& o) {
    if (o.frames) scene.time.frames = in_range("--frames", *o.frames, 1, limits::kMaxFrames);
    if (o.passes) scene.render.passes = in_range("--passes", *o.passes, 1, limits::kMaxPasses);
    if (o.width) scene.camera.width = in_range("--width", *o.width, 1, limits::kMaxImageSide);
    if (o.height) scene.camera.height = in_range("--height", *o.height, 1, limits::kMaxImageSide);
    if (o.photons)
        scene.render.photons_per_pass =
            in_range<int64_t>("--photons", *o.photons, 1, limits::kMaxPhotonsPerPass);
    if (o.max_depth) scene.render.max_depth = in_range("--max-depth", *o.max_depth, 1, limits::kMaxDepth);
    if (o.seed) scene.render.seed = *o.seed;
    if (o.camera_tof) scene.render.camera_tof = *o.camera_tof;
    if (o.emission) scene.emission = parse_emission_option(*o.emission);
    // New frames or a new width: the pulse must still be a whole number of frames.
    if (auto problem = check_pulse_width(scene.time, scene.emission))
        command_line_error(o.emission ? "--emission" : "--frames", *problem);
}

void apply_gltf_light_units(SceneDesc& scene, std::optional<LightUnits> units) {
    if (!units) return;
    for (ShapeDesc& s : scene.shapes)
        if (s.type == ShapeType::Gltf && !s.light_units) s.light_units = units;
}

void apply_gltf_principled(SceneDesc& scene, std::optional<PrincipledBase> principled) {
    if (!principled) return;
    for (ShapeDesc& s : scene.shapes)
        if (s.type == ShapeType::Gltf && s.material < 0 && !s.principled) s.principled = principled;
}

}  // namespace sl
