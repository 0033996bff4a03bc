// The in-process render that the tests, the benchmarks and the report use (render_frames) is
// the program's own: its frames and steady image equal, bit for bit, the EXR files
// `slowlight render` writes for the same scene and settings (EXR stores 32-bit floats), with
// one section, with several, and frame by frame. A second section loop that drifted from the
// program's (a layout, a seed, the assembly) would show here.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "config/command_line.h"
#include "config/parse_scene.h"
#include "pipeline/frames_in_memory.h"
#include "pipeline/render_frames.h"
#include "tests/pipeline/pipeline_helpers.h"

namespace sl::test {
namespace {

void expect_program_equals_in_process(const std::vector<std::string>& extra, const RenderRequest& request) {
    ScratchDir dir;
    const std::string scene_path = sample("cornell_box.json");
    std::vector<std::string> args = small_render(scene_path, extra, 6, 3, 3000);
    args.insert(args.end(), {"--exr-dir", (dir.path() / "exr").string()});
    ProgramResult r = run_program(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;

    std::vector<const char*> argv{"slowlight"};
    for (const std::string& a : args) argv.push_back(a.c_str());
    const RunOptions o = parse_command_line(static_cast<int>(argv.size()), argv.data());
    SceneDesc scene = parse_scene_file(scene_path);
    apply_overrides(scene, o.overrides);
    RenderContext ctx(scene);
    FramesInMemory sink;
    const PipelineStats stats = render_frames(ctx, request, sink);

    ASSERT_EQ(sink.frames.size(), 6u);
    EXPECT_EQ(stats.passes_run, request.strategy == Strategy::FrameByFrame ? 6 * 3 : request.sections * 3);
    EXPECT_GT(stats.counts.photons, 0u);
    for (int k = 0; k < 6; ++k) {
        const std::vector<float> written = summarize_exr((dir.path() / "exr" / frame_name(k)).string()).rgb;
        ASSERT_EQ(written.size(), sink.frames[k].size()) << "frame " << k;
        EXPECT_TRUE(written == sink.frames[k]) << "frame " << k << " differs";
    }
    EXPECT_TRUE(summarize_exr((dir.path() / "exr" / "steady.exr").string()).rgb == sink.steady);
}

TEST(OneRenderPath, InProcessFramesEqualTheProgramsOneSection) {
    expect_program_equals_in_process({"--sections", "1"}, {Strategy::Single, 1});
}

TEST(OneRenderPath, InProcessFramesEqualTheProgramsThreeSections) {
    expect_program_equals_in_process({"--sections", "3"}, {Strategy::Single, 3});
}

TEST(OneRenderPath, InProcessFramesEqualTheProgramsFrameByFrame) {
    expect_program_equals_in_process({"--strategy", "frame-by-frame"}, {Strategy::FrameByFrame});
}

}  // namespace
}  // namespace sl::test
