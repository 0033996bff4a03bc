#pragma once
// KHR_lights_punctual lights as slowlight lights. glTF gives point and spot intensity in
// candela and directional intensity in lux; at 683 lm/W that is cd / 683 W/sr (power =
// 4 pi cd / 683 for a point light) and lux / 683 W/m^2 (LightUnits::Photometric). Files written
// in radiometric units (LightUnits::Radiometric) are read as W/sr and W/m^2. Spot lights have a
// smooth falloff between the inner and outer cone: slowlight's spot is a hard cone of
// uniform intensity, so the cone is placed half-way between them (with a warning).
// Directional lights become `sun` lights of no angular size.
#include <optional>
#include <string>

#include "config/scene_desc.h"

namespace sl {

struct PunctualLight {
    std::string name, type;  // "point", "spot", "directional"
    Vec3 color{1, 1, 1};
    double intensity = 1;    // candela (point, spot) or lux (directional); W/sr or W/m^2 if radiometric
    double range = 0;        // 0: infinite
    double inner_cone = 0, outer_cone = 0.785398163397448;  // radians
    Vec3 position, direction;  // scene space; direction need not be unit
};

// The light, or nothing; `warning` (without "warning: ") says what was approximated or left out.
std::optional<LightDesc> map_punctual_light(const PunctualLight& l, LightUnits units, std::string& warning);

// Directional lights: kept apart so that the sun light can take them over in one place.
std::optional<LightDesc> map_directional_light(const PunctualLight& l, LightUnits units, std::string& warning);

// Watts per candela (per lux for directional lights): 1 / 683, or 1 for radiometric files.
double watts_per_unit(LightUnits units);

}  // namespace sl
