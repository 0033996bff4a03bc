// config/scene_fields.h must name every data member of the scene's structs: the resume
// fingerprint serializes what it names, so a member it forgets would let --resume mix frames
// of two different renders. The compiler counts each struct's members here.
#include <gtest/gtest.h>

#include <cstddef>

#include "config/scene_fields.h"

namespace {

// Converts to any member type, so T{AnyField{}, ...} compiles exactly up to T's member count.
struct AnyField {
    template <class T>
    operator T() const;
};

template <class T, class... Fields>
constexpr size_t member_count() {
    if constexpr (requires { T{Fields{}..., AnyField{}}; })
        return member_count<T, Fields..., AnyField>();
    else
        return sizeof...(Fields);
}

template <class T>
size_t visited_count() {
    size_t n = 0;
    sl::visit_fields(T{}, [&](const char*, const auto&) { ++n; });
    return n;
}

}  // namespace

TEST(SceneFields, EveryMemberOfEveryStructIsVisited) {
    using namespace sl;
    EXPECT_EQ(visited_count<CameraDesc>(), member_count<CameraDesc>());
    EXPECT_EQ(visited_count<MaterialDesc>(), member_count<MaterialDesc>());
    EXPECT_EQ(visited_count<TextureDesc>(), member_count<TextureDesc>());
    EXPECT_EQ(visited_count<ShapeDesc>(), member_count<ShapeDesc>());
    EXPECT_EQ(visited_count<LightDesc>(), member_count<LightDesc>());
    EXPECT_EQ(visited_count<MediumDesc>(), member_count<MediumDesc>());
    EXPECT_EQ(visited_count<TimeDesc>(), member_count<TimeDesc>());
    EXPECT_EQ(visited_count<EmissionDesc>(), member_count<EmissionDesc>());
    EXPECT_EQ(visited_count<RenderDesc>(), member_count<RenderDesc>());
    EXPECT_EQ(visited_count<SceneDesc>(), member_count<SceneDesc>());
}

TEST(SceneFields, TheCountSeesAnAddedMember) {
    // The guard itself: a struct one member longer than another counts one more.
    struct Two { int a = 0; sl::Vec3 b; };
    struct Three { int a = 0; sl::Vec3 b; std::string c; };
    EXPECT_EQ(member_count<Two>(), 2u);
    EXPECT_EQ(member_count<Three>(), 3u);
    EXPECT_EQ(member_count<sl::CameraDesc>(), 6u);  // position, look_at, up, vfov_deg, width, height
}
