// The resume fingerprint is made from every field of the settings: changing any field that
// decides pixels refuses old frames, changing one that does not (a name, a path, the video's
// fps) keeps them. Each field is changed in turn, found through the same field list the
// fingerprint uses, so a field the list names but the fingerprint drops fails here.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <type_traits>

#include "config/scene_fields.h"
#include "pipeline/settings_fingerprint.h"

namespace {

using namespace sl;

// A scene with one of every list's elements, reading no file.
SceneDesc one_of_each() {
    SceneDesc s;
    s.source = "test.json";
    s.materials.push_back(MaterialDesc{});
    s.materials[0].name = "white";
    ShapeDesc quad;
    quad.edge1 = Vec3(1, 0, 0);
    quad.edge2 = Vec3(0, 0, 1);
    s.shapes.push_back(quad);
    LightDesc light;
    light.type = LightType::Quad;
    s.lights.push_back(light);
    s.textures.push_back(TextureDesc{});
    s.textures[0].file = "albedo.png";
    return s;
}

// Changes one value of a leaf field; false for lists, optionals and pointers (not leaves).
template <class T>
bool change(T& v) {
    if constexpr (std::is_same_v<T, bool>) v = !v;
    else if constexpr (std::is_enum_v<T>) v = static_cast<T>(static_cast<int>(v) + 1);
    else if constexpr (std::is_arithmetic_v<T>) v = static_cast<T>(v + 1);
    else if constexpr (std::is_same_v<T, Vec3>) v.y += 1;
    else if constexpr (std::is_same_v<T, std::string>) v += "x";
    else return false;
    return true;
}

// Changes field number `index` of struct x (in visit_fields order); false when it is no leaf.
template <class S>
bool change_field(S& x, size_t index, std::string& name) {
    size_t i = 0;
    bool changed = false;
    visit_fields(x, [&](const char* field, const auto& v) {
        if (i++ != index) return;
        name = field;
        using T = std::remove_cvref_t<decltype(v)>;
        changed = change(const_cast<T&>(v));  // x itself is not const: the list takes const refs
    });
    return changed;
}

template <class S>
size_t field_count(const S& x) {
    size_t n = 0;
    visit_fields(x, [&](const char*, const auto&) { ++n; });
    return n;
}

// Changes each leaf field of the struct `pick(scene)` in turn; returns the paths whose change
// left the fingerprint as it was, and counts the fields changed.
template <class Pick>
std::set<std::string> unchanged_fields(const std::string& prefix, Pick pick, int& changed) {
    const SceneDesc base = one_of_each();
    const std::string before = settings_fingerprint(base, 1, Strategy::Single);
    std::set<std::string> same;
    SceneDesc probe = base;
    const size_t n = field_count(pick(probe));
    for (size_t k = 0; k < n; ++k) {
        SceneDesc s = base;
        std::string name;
        if (!change_field(pick(s), k, name)) continue;
        ++changed;
        if (settings_fingerprint(s, 1, Strategy::Single) == before) same.insert(prefix + name);
    }
    return same;
}

}  // namespace

TEST(SettingsFingerprint, EveryFieldThatDecidesPixelsChangesIt) {
    int changed = 0;
    std::set<std::string> same;
    auto add = [&](const std::set<std::string>& s) { same.insert(s.begin(), s.end()); };
    add(unchanged_fields("", [](SceneDesc& s) -> SceneDesc& { return s; }, changed));
    add(unchanged_fields("camera.", [](SceneDesc& s) -> CameraDesc& { return s.camera; }, changed));
    add(unchanged_fields("materials[].", [](SceneDesc& s) -> MaterialDesc& { return s.materials[0]; }, changed));
    add(unchanged_fields("shapes[].", [](SceneDesc& s) -> ShapeDesc& { return s.shapes[0]; }, changed));
    add(unchanged_fields("lights[].", [](SceneDesc& s) -> LightDesc& { return s.lights[0]; }, changed));
    add(unchanged_fields("textures[].", [](SceneDesc& s) -> TextureDesc& { return s.textures[0]; }, changed));
    add(unchanged_fields("medium.", [](SceneDesc& s) -> MediumDesc& { return s.medium; }, changed));
    add(unchanged_fields("time.", [](SceneDesc& s) -> TimeDesc& { return s.time; }, changed));
    add(unchanged_fields("emission.", [](SceneDesc& s) -> EmissionDesc& { return s.emission; }, changed));
    add(unchanged_fields("render.", [](SceneDesc& s) -> RenderDesc& { return s.render; }, changed));
    // The only fields that decide no pixel: names, paths (the files' bytes are hashed), fps,
    // where an import's lights went (the lights are in it).
    const std::set<std::string> expected = {"source",        "imports_resolved", "materials[].name",
                                            "shapes[].file", "textures[].file",  "time.fps",
                                            "shapes[].first_light", "shapes[].light_count"};
    EXPECT_EQ(same, expected);
    EXPECT_EQ(changed, 83);  // every leaf of every struct was tried (71, 10 GGX material fields, 2 normal map)
}

TEST(SettingsFingerprint, SectionsAndStrategyChangeIt) {
    const SceneDesc s = one_of_each();
    const std::string a = settings_fingerprint(s, 1, Strategy::Single);
    EXPECT_EQ(a.size(), 16u);
    EXPECT_EQ(settings_fingerprint(s, 1, Strategy::Single), a);  // deterministic
    EXPECT_NE(settings_fingerprint(s, 2, Strategy::Single), a);
    EXPECT_NE(settings_fingerprint(s, 1, Strategy::FrameByFrame), a);
}

TEST(SettingsFingerprint, CanonicalTextHasSortedKeys) {
    const std::string text = canonical_settings(one_of_each(), 1, Strategy::Single);
    EXPECT_LT(text.find("\"camera\""), text.find("\"emission\""));
    EXPECT_LT(text.find("\"emission\""), text.find("\"lights\""));
    EXPECT_EQ(text.find("\"source\""), std::string::npos);   // decides no pixel
    EXPECT_NE(text.find("\"width_frames\""), std::string::npos);
}
