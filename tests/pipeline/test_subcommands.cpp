// What a new user meets first: `slowlight` alone lists the commands, each command has its own
// --help and refuses options it would ignore, `info` on a cube points to `retime`, a render
// without any output refuses to start, and every run ends with a line saying what it wrote.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <regex>

#include "tests/pipeline/pipeline_helpers.h"

using namespace sl::test;

namespace {

std::string last_line(const std::string& text) {
    std::string t = text;
    while (!t.empty() && t.back() == '\n') t.pop_back();
    size_t nl = t.rfind('\n');
    return nl == std::string::npos ? t : t.substr(nl + 1);
}

}  // namespace

TEST(Subcommands, AloneListsEveryCommand) {
    ScratchDir dir;
    ProgramResult r = run_program({}, dir.file("stdout.txt"));
    SL_EXPECT_EXIT(r, 2);
    EXPECT_EQ(r.error_lines().size(), 1u) << r.err;
    std::ifstream f(dir.file("stdout.txt"));
    const std::string out((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    for (const char* c : {"slowlight render", "slowlight info", "slowlight retime", "--help"})
        EXPECT_NE(out.find(c), std::string::npos) << c << " missing from:\n" << out;
}

TEST(Subcommands, EachHasItsOwnHelpWithOnlyItsOptions) {
    ScratchDir dir;
    const std::string out = dir.file("help.txt");
    SL_EXPECT_EXIT(run_program({"retime", "--help"}, out), 0);
    std::string help = read_text(out);
    EXPECT_EQ(help.rfind("slowlight retime CUBE.npy", 0), 0u) << help;
    EXPECT_NE(help.find("--emission"), std::string::npos);
    EXPECT_EQ(help.find("--sections"), std::string::npos) << "retime's help lists --sections";
    EXPECT_EQ(help.find("--camera-tof"), std::string::npos);

    SL_EXPECT_EXIT(run_program({"info", "--help"}, out), 0);
    help = read_text(out);
    EXPECT_EQ(help.rfind("slowlight info SCENE.json", 0), 0u) << help;
    EXPECT_NE(help.find("--max-memory"), std::string::npos);
    EXPECT_EQ(help.find("--output"), std::string::npos) << "info's help lists --output";

    SL_EXPECT_EXIT(run_program({"--help"}, out), 0);
    EXPECT_NE(read_text(out).find("docs/scene-format.md"), std::string::npos) << "--help does not point to the format";
}

TEST(Subcommands, RefuseOptionsTheyWouldIgnore) {
    const std::string scene = sample("cornell_box.json");
    const std::pair<std::vector<std::string>, std::string> cases[] = {
        {{"info", scene, "--sections", "3", "-o", "x.mp4"}, "error: command line: info does not use --sections"},
        {{"info", scene, "-o", "x.mp4"}, "error: command line: info does not use --output"},
        {{"retime", "cube.npy", "--camera-tof", "-o", "x.mp4"}, "error: command line: retime does not use --camera-tof"},
        {{"retime", "cube.npy", "--passes", "3", "-o", "x.mp4"}, "error: command line: retime does not use --passes"},
        {{"render", "--fames", "3"}, "error: command line: unknown option '--fames': did you mean --frames?"},
    };
    for (const auto& [args, message] : cases) {
        ProgramResult r = run_program(args);
        SL_EXPECT_EXIT(r, 2);
        ASSERT_EQ(r.error_lines().size(), 1u) << r.err;
        EXPECT_EQ(r.error_lines()[0].rfind(message, 0), 0u) << r.error_lines()[0];
    }
}

TEST(Subcommands, InfoOnACubePointsToRetime) {
    ScratchDir dir;
    const std::string cube = dir.file("c.npy");
    SL_EXPECT_EXIT(run_program(small_render("", {"--cube", cube}, 2, 1, 500, 8, 8)), 0);
    for (const std::string& path : {cube, dir.file("c.npy.json")}) {
        if (path.ends_with(".json")) continue;
        ProgramResult r = run_program({"info", path});
        SL_EXPECT_EXIT(r, 2);
        ASSERT_EQ(r.error_lines().size(), 1u) << r.err;
        EXPECT_NE(r.err.find("slowlight retime " + cube), std::string::npos) << r.err;
    }
    // A cube renamed: recognised by its contents, not its name.
    std::filesystem::copy_file(cube, dir.file("renamed.bin"));
    ProgramResult r = run_program({"info", dir.file("renamed.bin")});
    SL_EXPECT_EXIT(r, 2);
    EXPECT_NE(r.err.find("is a transient cube"), std::string::npos) << r.err;
}

TEST(Subcommands, RenderAndRetimeWithoutAnyOutputRefuseToStart) {
    ProgramResult r = run_program(small_render("", {}, 2, 1, 500, 8, 8));
    SL_EXPECT_EXIT(r, 2);
    ASSERT_EQ(r.error_lines().size(), 1u) << r.err;
    EXPECT_NE(r.err.find("add -o out.mp4"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("section 1/"), std::string::npos) << "it rendered anyway";
    ScratchDir dir;
    const std::string cube = dir.file("c.npy");
    SL_EXPECT_EXIT(run_program(small_render("", {"--cube", cube}, 2, 1, 500, 8, 8)), 0);
    r = run_program({"retime", cube, "--emission", "pulse"});
    SL_EXPECT_EXIT(r, 2);
    EXPECT_NE(r.err.find("retime writes nothing without an output"), std::string::npos) << r.err;
}

TEST(Subcommands, FinalLineSaysWhatWasWrittenHowManyFramesAndHowLong) {
    ScratchDir dir;
    const std::string video = dir.file("v.mkv"), cube = dir.file("c.npy");
    ProgramResult r = run_program(small_render("", {"-o", video, "--exr-dir", dir.file("exr"), "--cube", cube}, 3, 1, 500, 8, 8));
    SL_EXPECT_EXIT(r, 0);
    std::string line = last_line(r.err);
    EXPECT_TRUE(std::regex_search(line, std::regex("^slowlight: wrote .*v\\.mkv \\(3 frames\\), .*exr/ \\(3 frames as EXR, "
                                                   "and steady\\.exr\\), .*c\\.npy .* in [0-9]+\\.[0-9] s$")))
        << line;
    r = run_program({"retime", cube, "--emission", "pulse", "-o", dir.file("p.mkv")});
    SL_EXPECT_EXIT(r, 0);
    EXPECT_TRUE(std::regex_search(last_line(r.err), std::regex("^slowlight: wrote .*p\\.mkv \\(3 frames\\) in [0-9.]+ s$")))
        << r.err;
}

// Every EXR frame says when it starts and ends, and with which exposure and curve it was shown.
TEST(Subcommands, ExrFramesCarryTheirStartEndAndExposure) {
    ScratchDir dir;
    ProgramResult r = run_program(small_render(sample("cornell_box.json"),
                                               {"--exr-dir", dir.file("exr"), "-o", dir.file("v.mkv"), "--tone", "filmic"},
                                               4, 1, 500, 8, 8));
    SL_EXPECT_EXIT(r, 0);
    // The box's window, 0 to 24 ns in 4 frames: frame 2 covers [12, 18) ns.
    sl::ExrImage f = sl::read_exr(dir.file("exr/frame_0002.exr"));
    EXPECT_DOUBLE_EQ(std::stod(f.metadata.at("slowlight:frame_start_ns")), 12.0);
    EXPECT_DOUBLE_EQ(std::stod(f.metadata.at("slowlight:frame_end_ns")), 18.0);
    EXPECT_GT(std::stod(f.metadata.at("slowlight:exposure")), 0.0);
    EXPECT_EQ(f.metadata.at("slowlight:tone"), "filmic");
}

// `info --max-memory SIZE` names the K a render would pick, and that render picks it and stays
// within SIZE: --max-memory bounds the whole process.
TEST(Subcommands, InfoSaysWhichSectionCountAMemoryBudgetGives) {
    ScratchDir dir;
    const std::string scene = sample("cornell_box.json"), out = dir.file("info.txt");
    SL_EXPECT_EXIT(run_program({"info", scene, "--max-memory", "8G"}, out), 0);
    EXPECT_NE(read_text(out).find("with --max-memory 8.00 GiB: K = 1"), std::string::npos) << read_text(out);
    // The whole process of K = 1 and K = 2, as info states them; a budget between them gives K = 2.
    SL_EXPECT_EXIT(run_program({"info", scene}, out), 0);
    const std::string text = read_text(out);
    std::smatch m1, m2;
    ASSERT_TRUE(std::regex_search(text, m1, std::regex(R"(\n  1 .*about ([0-9.]+) MiB\n)"))) << text;
    ASSERT_TRUE(std::regex_search(text, m2, std::regex(R"(\n  2 .*about ([0-9.]+) MiB\n)"))) << text;
    const double whole1 = std::stod(m1[1]), whole2 = std::stod(m2[1]);
    ASSERT_GT(whole1, whole2);
    const std::string budget = std::to_string(static_cast<long long>((whole1 + whole2) / 2 * 1048576.0));
    SL_EXPECT_EXIT(run_program({"info", scene, "--max-memory", budget}, out), 0);
    EXPECT_NE(read_text(out).find(": K = 2 "), std::string::npos) << read_text(out);
}
