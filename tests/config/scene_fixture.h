#pragma once
// A scene that uses every key of the format, and a temporary folder holding its mesh file.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace sl::test {

// Every shape, light and section; time 0..24 ns in 48 frames (Δ = 0.5 ns), pulse of 1 ns.
inline nlohmann::json full_scene() {
    return nlohmann::json::parse(R"({
      "units":  {"meters_per_unit": 1.0},
      "camera": {"position": [0, 1, 3.5], "look_at": [0, 1, 0], "up": [0, 2, 0],
                 "vfov_deg": 40, "width": 64, "height": 48},
      "materials": {
        "white":  {"type": "diffuse", "albedo": [0.7, 0.7, 0.7]},
        "mirror": {"type": "mirror", "reflectance": [0.9, 0.9, 0.9]},
        "glass":  {"type": "dielectric", "ior": 1.5}
      },
      "shapes": [
        {"type": "quad",   "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2], "material": "white"},
        {"type": "box",    "min": [-0.5, 0, -0.5], "max": [0.5, 1, 0.5], "material": "mirror"},
        {"type": "sphere", "center": [0, 1.5, 0], "radius": 0.3, "material": "glass"},
        {"type": "mesh",   "file": "meshes/thing.obj", "translate": [1, 0, 0], "scale": 2,
                           "rotate_deg": [0, 90, 0], "material": "white"}
      ],
      "lights": [
        {"type": "point", "position": [0, 1.9, 0], "power": [10, 10, 10]},
        {"type": "quad",  "corner": [-0.25, 1.98, -0.2], "edge1": [0.5, 0, 0], "edge2": [0, 0, 0.4],
                          "radiance": [17, 12, 4]},
        {"type": "spot",  "position": [0, 1.9, 0], "direction": [0, -3, 0], "cone_deg": 20, "power": [5, 5, 5]},
        {"type": "laser", "position": [0, 1, 1], "direction": [0, 0, -1], "radius": 0.002, "power": [1, 0, 0]}
      ],
      "medium": {"sigma_a": 0.01, "sigma_s": [0.05, 0.06, 0.07], "g": 0.3,
                 "bounds": {"min": [-1, 0, -1], "max": [1, 2, 1]}},
      "time":     {"start_ns": 0, "end_ns": 24, "frames": 48, "fps": 24},
      "emission": {"mode": "pulse", "width_ns": 1},
      "render":   {"passes": 16, "photons_per_pass": 1000, "max_depth": 5, "radius": 0.02,
                   "alpha": 0.7, "camera_tof": true, "seed": 7, "ambient": [0.1, 0.1, 0.1]}
    })");
}

// A fresh folder with meshes/thing.obj (and an empty folder meshes/dir.obj), removed after.
class SceneFolder : public ::testing::Test {
protected:
    void SetUp() override {
        std::string pattern =
            (std::filesystem::temp_directory_path() / "slowlight_config_XXXXXX").string();
        ASSERT_NE(mkdtemp(pattern.data()), nullptr);
        dir = pattern;
        std::filesystem::create_directories(dir / "meshes" / "dir.obj");
        std::ofstream(dir / "meshes" / "thing.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    }
    void TearDown() override { std::filesystem::remove_all(dir); }

    std::filesystem::path dir;
};

}  // namespace sl::test
