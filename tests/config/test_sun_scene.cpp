// The scene file's sun: its direction (where the light goes) is normalised, and a disc radiance
// becomes the irradiance E = L pi sin^2(angle / 2) that the renderer uses.
#include <gtest/gtest.h>

#include <cmath>

#include "foundation/constants.h"
#include "config/parse_scene.h"

using namespace sl;

namespace {

SceneDesc with_light(const std::string& light) {
    return parse_scene_text(R"({"camera": {"position": [0, 1, 3], "look_at": [0, 1, 0]},
                               "materials": {"w": {"type": "diffuse"}},
                               "shapes": [{"type": "quad", "corner": [-1, 0, 1], "edge1": [2, 0, 0],
                                           "edge2": [0, 0, -2], "material": "w"}],
                               "lights": [)" + light + "]}",
                            "sun.json", "");
}

}  // namespace

TEST(SunScene, IrradianceAndDirectionAsGiven) {
    SceneDesc s = with_light(R"({"type": "sun", "direction": [0, -2, 0], "irradiance": [900, 800, 700]})");
    ASSERT_EQ(s.lights.size(), 1u);
    const LightDesc& l = s.lights[0];
    EXPECT_EQ(l.type, LightType::Sun);
    EXPECT_FLOAT_EQ(l.direction.y, -1.0f);
    EXPECT_FLOAT_EQ(l.angle_deg, 0.53f);  // the sun's own, when omitted
    EXPECT_FLOAT_EQ(l.irradiance.x, 900.0f);
    EXPECT_FLOAT_EQ(l.irradiance.z, 700.0f);
}

TEST(SunScene, RadianceOfTheDiscBecomesIrradiance) {
    // A disc of 0.53 degrees: solid angle ~ 6.72e-5 sr; L = 1.5e7 W/sr/m^2 gives ~1008 W/m^2.
    SceneDesc s = with_light(R"({"type": "sun", "direction": [1, -1, 0], "angle_deg": 0.53, "radiance": [1.5e7, 1.5e7, 1.5e7]})");
    const double half = 0.5 * 0.53 * sl::kPiDouble / 180;
    const double want = 1.5e7 * sl::kPiDouble * std::sin(half) * std::sin(half);
    EXPECT_NEAR(s.lights[0].irradiance.x, want, 1e-5 * want);
    EXPECT_NEAR(want, 1008.5, 1.0);
}
