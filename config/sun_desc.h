#pragma once
// A sun as the scene describes it (the renderer's SunLight in core/ is built from this): kept
// with the parsed description so that the parser and the importers make suns the same way.
#include <cmath>

#include "config/scene_desc.h"
#include "foundation/constants.h"

namespace sl {

// A sun light as the scene file (or an importer) describes it: travel direction (any length),
// angular diameter in degrees (0.53 for the sun seen from the earth; 0 for a perfectly
// collimated light) and irradiance in W/m^2 on a plane facing the light.
inline LightDesc make_sun_light(Vec3 direction, float angle_deg, Vec3 irradiance) {
    LightDesc l;
    l.type = LightType::Sun;
    l.direction = normalize(direction);
    l.angle_deg = angle_deg;
    l.irradiance = irradiance;
    return l;
}

// The irradiance of a sun disc of uniform radiance L (W sr^-1 m^-2) and angular diameter
// angle_deg: E = L pi sin^2(angle/2).
inline Vec3 sun_irradiance_from_radiance(Vec3 radiance, float angle_deg) {
    const double s = std::sin(0.5 * angle_deg * kPiDouble / 180.0);
    return radiance * static_cast<float>(kPiDouble * s * s);
}

}  // namespace sl
