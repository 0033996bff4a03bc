#pragma once
namespace sl {
// The built-in demo (samples/cornell_box.json), used when `slowlight render` names no scene.
const char* default_scene_json();
}  // namespace sl
