#pragma once
// The keys the scene parser accepts, per JSON object (and per "type" for materials, shapes and
// lights). config/parse_scene.cpp checks every object against these lists and nothing else, so
// they are the whole truth about the format: tests/docs/ checks docs/scene-format.md against
// them in both directions, and an unknown key's message lists them.
#include <span>
#include <string_view>

namespace sl {

struct SceneObjectKeys {
    std::string_view object;  // "" (the top level), "camera", "shapes", "medium.bounds", ...
    std::string_view type;    // the value of its "type" key, or "" for an object without types
    std::span<const std::string_view> keys;
};

// Every object the parser reads, in the order of docs/scene-format.md.
std::span<const SceneObjectKeys> scene_object_keys();

// The keys of one object (and type); std::logic_error for a pair the list does not have.
std::span<const std::string_view> scene_keys_of(std::string_view object, std::string_view type = {});

}  // namespace sl
