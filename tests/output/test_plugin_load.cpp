// core/plugin.h, the one loader of our plugins: a plugin beside the program loads and yields
// its entry points; a missing plugin or entry point is one message naming what is missing.
#include "core/plugin.h"

#include <gtest/gtest.h>

namespace sl {
namespace {

TEST(PluginLoad, FindsThePluginBesideTheProgramAndItsEntryPoints) {
    // The test programs are built beside the plugins, as slowlight is.
    const Plugin p = load_plugin("libslowlight_label.so", "the label writer",
                                 {"slowlight_label_open", "slowlight_label_burn", "slowlight_label_close"});
    ASSERT_EQ(p.error, "");
    ASSERT_EQ(p.symbols.size(), 3u);
    for (void* s : p.symbols) EXPECT_NE(s, nullptr);
    using CloseFn = void (*)(void*);
    EXPECT_NE(p.function<CloseFn>(2), nullptr);
}

TEST(PluginLoad, AMissingEntryPointIsNamed) {
    const Plugin p = load_plugin("libslowlight_png.so", "the PNG writer", {"slowlight_png_write", "slowlight_no_such"});
    EXPECT_EQ(p.error, "the PNG writer libslowlight_png.so has no slowlight_no_such");
    using Fn = int (*)();
    EXPECT_EQ(p.function<Fn>(0), nullptr) << "nothing of a plugin that failed is used";
}

TEST(PluginLoad, AMissingPluginIsNamedWithTheLoadersReason) {
    const Plugin p = load_plugin("libslowlight_no_such.so", "the test plugin", {"anything"});
    EXPECT_EQ(p.error.rfind("cannot load the test plugin libslowlight_no_such.so: ", 0), 0u) << p.error;
    EXPECT_NE(p.error.find("libslowlight_no_such.so: cannot open shared object file"), std::string::npos) << p.error;
    EXPECT_TRUE(p.symbols.empty());
}

}  // namespace
}  // namespace sl
