// Mistakes are caught before any rendering: the right exit status, exactly one `error:` line on
// stderr that names what is wrong, and no output file left behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/pipeline/pipeline_helpers.h"

namespace fs = std::filesystem;
using namespace sl::test;

namespace {

// One `error:` line, and no sign that rendering began.
void expect_one_error_before_rendering(const ProgramResult& r) {
    EXPECT_FALSE(r.timed_out);
    std::vector<std::string> errors = r.error_lines();
    EXPECT_EQ(errors.size(), 1u) << "stderr:\n" << r.err;
    EXPECT_EQ(r.err.find("section 1/"), std::string::npos) << "rendering started:\n" << r.err;
    EXPECT_NE(r.exit_code, 0);
    EXPECT_LT(r.exit_code, 128) << "killed by a signal:\n" << r.err;
}

}  // namespace

// Every output is checked before rendering, and one that cannot be written is refused like
// any other bad argument (exit 2), not found after the render.
TEST(Errors, OutputInMissingDirectoryIsRefusedBeforeRendering) {
    ScratchDir dir;
    const std::string missing = dir.file("no_such_dir");
    const std::string video = missing + "/out.mp4";
    ProgramResult r = run_program(small_render("", {"-o", video}));
    SL_EXPECT_EXIT(r, 2);
    expect_one_error_before_rendering(r);
    ASSERT_EQ(r.error_lines().size(), 1u);
    EXPECT_NE(r.error_lines()[0].find(video), std::string::npos) << "the error should name the path";
    EXPECT_FALSE(fs::exists(video));
    EXPECT_FALSE(fs::exists(missing));
    EXPECT_TRUE(fs::is_empty(dir.path())) << "something was left behind";
}

TEST(Errors, UnknownVideoExtensionIsInvalidInput) {
    ScratchDir dir;
    const std::string video = dir.file("out.xyz");
    ProgramResult r = run_program(small_render("", {"-o", video}));
    SL_EXPECT_EXIT(r, 2);
    expect_one_error_before_rendering(r);
    ASSERT_EQ(r.error_lines().size(), 1u);
    EXPECT_NE(r.error_lines()[0].find("xyz"), std::string::npos) << "the error should name the extension";
    EXPECT_TRUE(fs::is_empty(dir.path())) << "something was left behind";
}

TEST(Errors, UnknownSceneKeyNamesFileAndKey) {
    ScratchDir dir;
    std::string text = read_text(sample("cornell_box.json"));
    const std::string anchor = "\"render\":   {";
    size_t at = text.find(anchor);
    ASSERT_NE(at, std::string::npos) << "samples/cornell_box.json changed shape";
    text.insert(at + anchor.size(), "\"bogus_setting\": 3, ");
    const std::string scene = dir.file("bad_key.json");
    std::ofstream(scene) << text;
    const std::string video = dir.file("out.mp4");

    ProgramResult r = run_program(small_render(scene, {"-o", video, "--exr-dir", dir.file("exr")}));
    SL_EXPECT_EXIT(r, 2);
    expect_one_error_before_rendering(r);
    ASSERT_EQ(r.error_lines().size(), 1u);
    const std::string line = r.error_lines()[0];
    EXPECT_NE(line.find(scene), std::string::npos) << "should name the file: " << line;
    EXPECT_NE(line.find("bogus_setting"), std::string::npos) << "should name the key: " << line;
    EXPECT_FALSE(fs::exists(video));
    EXPECT_FALSE(fs::exists(dir.file("exr")));
}

TEST(Errors, MissingSceneFileIsInvalidInput) {
    ScratchDir dir;
    const std::string scene = dir.file("nowhere.json");
    ProgramResult r = run_program(small_render(scene, {"-o", dir.file("out.mp4")}));
    SL_EXPECT_EXIT(r, 2);
    expect_one_error_before_rendering(r);
    ASSERT_EQ(r.error_lines().size(), 1u);
    EXPECT_NE(r.error_lines()[0].find(scene), std::string::npos) << "should name the file";
    EXPECT_FALSE(fs::exists(dir.file("out.mp4")));
}

// Command-line values that cannot work are invalid input too, caught before rendering.
TEST(Errors, BadSectionOptionsAreInvalidInput) {
    ScratchDir dir;
    for (std::vector<std::string> extra : {std::vector<std::string>{"--sections", "0"},
                                           std::vector<std::string>{"--sections", "5"},  // > 4 frames
                                           std::vector<std::string>{"--max-memory", "lots"},
                                           std::vector<std::string>{"--strategy", "sideways"}}) {
        SCOPED_TRACE(extra[0] + " " + extra[1]);
        extra.insert(extra.end(), {"-o", dir.file("out.mp4")});
        ProgramResult r = run_program(small_render("", extra));
        SL_EXPECT_EXIT(r, 2);
        expect_one_error_before_rendering(r);
        ASSERT_EQ(r.error_lines().size(), 1u);
        EXPECT_NE(r.error_lines()[0].find(extra[0]), std::string::npos) << "should name the option";
        EXPECT_FALSE(fs::exists(dir.file("out.mp4")));
    }
}
