#include "core/import/light_mapping.h"

#include <cmath>

#include "foundation/constants.h"
#include "core/sun_light.h"

namespace sl {

namespace {
std::string label(const PunctualLight& l) {
    return "light '" + (l.name.empty() ? l.type : l.name) + "'";
}
}  // namespace

double watts_per_unit(LightUnits units) { return units == LightUnits::Photometric ? 1 / kLumensPerWatt : 1.0; }

// A directional light is a sun with no angular size: its intensity is the illuminance (lux) or
// irradiance (W m^-2) on a plane facing it, and its wavefront enters the scene's bounds at t = 0.
std::optional<LightDesc> map_directional_light(const PunctualLight& l, LightUnits units, std::string& warning) {
    if (!(l.intensity >= 0) || !std::isfinite(l.intensity) || !is_finite(l.color) || !is_finite(l.direction) ||
        !(length(l.direction) > 0)) {
        warning = label(l) + ": intensity, colour or direction not finite (left out)";
        return std::nullopt;
    }
    return make_sun_light(l.direction, 0.0f,
                          vmax(l.color, Vec3(0)) * static_cast<float>(l.intensity * watts_per_unit(units)));
}

std::optional<LightDesc> map_punctual_light(const PunctualLight& l, LightUnits units, std::string& warning) {
    warning.clear();
    if (l.type == "directional") return map_directional_light(l, units, warning);
    if (!(l.intensity >= 0) || !std::isfinite(l.intensity) || !is_finite(l.color) || !is_finite(l.position))
        { warning = label(l) + ": intensity, colour or position not finite (left out)"; return std::nullopt; }
    const Vec3 intensity = vmax(l.color, Vec3(0)) * static_cast<float>(l.intensity * watts_per_unit(units));  // W/sr
    LightDesc d;
    d.position = l.position;
    if (l.type == "point") {
        d.type = LightType::Point;
        d.power = intensity * static_cast<float>(4 * kPiDouble);
    } else if (l.type == "spot") {
        Vec3 dir = l.direction;
        if (!(length(dir) > 0)) { warning = label(l) + ": no direction (left out)"; return std::nullopt; }
        if (!std::isfinite(l.inner_cone) || !std::isfinite(l.outer_cone))
            { warning = label(l) + ": cone angles not finite (left out)"; return std::nullopt; }
        d.type = LightType::Spot;
        d.direction = normalize(dir);
        double outer = std::clamp(l.outer_cone, 1e-3, kPiDouble / 2);
        double inner = std::clamp(l.inner_cone, 0.0, outer);
        double cone = 0.5 * (inner + outer);
        d.cone_deg = static_cast<float>(cone * 180 / kPiDouble);
        // The same intensity inside a hard cone: power = I 2 pi (1 - cos cone).
        double half = 0.5 * cone;
        d.power = intensity * static_cast<float>(2 * kPiDouble * 2 * std::sin(half) * std::sin(half));
        if (l.inner_cone > outer)
            warning = label(l) + ": its inner cone (" + std::to_string(l.inner_cone * 180 / kPiDouble).substr(0, 5) +
                      " deg) is wider than its outer cone (" + std::to_string(outer * 180 / kPiDouble).substr(0, 5) +
                      " deg): drawn as a hard cone of the outer angle";
        else if (outer - inner > 1e-3)
            warning = label(l) + ": the falloff from the inner (" + std::to_string(inner * 180 / kPiDouble).substr(0, 5) +
                      " deg) to the outer cone (" + std::to_string(outer * 180 / kPiDouble).substr(0, 5) +
                      " deg) is drawn as a hard cone of " + std::to_string(d.cone_deg).substr(0, 5) + " deg";
    } else {
        warning = label(l) + ": unknown type '" + l.type + "' (left out)";
        return std::nullopt;
    }
    if (l.range > 0) warning += std::string(warning.empty() ? label(l) + ": " : "; ") + "range is ignored (light reaches everywhere)";
    return d;
}

}  // namespace sl
