// --max-memory is reproducible: the plan is computed from the scene and the flags alone, never
// from what the process happens to have mapped, so the same scene and flags pick the same K.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <regex>

#include "config/parse_scene.h"
#include "core/import/resolve_imports.h"
#include "pipeline/memory_plan.h"
#include "tests/pipeline/pipeline_helpers.h"

using namespace sl::test;

namespace {

sl::SceneDesc cornell_box() {
    sl::SceneDesc scene = sl::parse_scene_file(sample("cornell_box.json"));
    sl::resolve_imports(scene);
    scene.time.frames = 96;
    return scene;
}

}  // namespace

// Plan, map and touch 200 MiB of unrelated memory, plan again: the same K and the same bytes,
// term by term. (The plan used to add the live resident size, so this moved K and every figure.)
TEST(MemoryPlan, SameKWhateverElseTheProcessHolds) {
    const sl::SceneDesc scene = cornell_box();
    sl::RunOptions o;
    o.output = "out.mp4";
    // Between K = 1's and K = 2's whole need: K = 2, and 200 MiB more RSS counted would change it.
    const uint64_t b1 = sl::section_buffer_bytes(scene, 1), b2 = sl::section_buffer_bytes(scene, 2);
    const uint64_t fixed = sl::memory_baseline(scene, o).total();
    o.max_memory_bytes = fixed + (b1 + b2) / 2;

    const sl::MemoryPlan first = sl::plan_memory(scene, o);
    constexpr size_t kBallast = size_t{200} << 20;
    std::unique_ptr<char[]> ballast(new char[kBallast]);
    std::memset(ballast.get(), 1, kBallast);  // touched: resident
    const sl::MemoryPlan second = sl::plan_memory(scene, o);
    EXPECT_NE(ballast[kBallast - 1], 0);

    EXPECT_EQ(first.sections, 2);
    EXPECT_EQ(second.sections, first.sections);
    EXPECT_EQ(second.fixed_overhead_bytes, first.fixed_overhead_bytes);
    EXPECT_EQ(second.buffer_bytes_per_section, first.buffer_bytes_per_section);
    EXPECT_EQ(second.bucket_budget, first.bucket_budget);
    EXPECT_EQ(second.total(), first.total());
    const auto t1 = first.fixed.terms(), t2 = second.fixed.terms();
    ASSERT_EQ(t1.size(), t2.size());
    for (size_t i = 0; i < t1.size(); ++i) EXPECT_EQ(t1[i].second, t2[i].second) << t1[i].first;
    EXPECT_EQ(first.fixed.total(), first.fixed_overhead_bytes);
}

// The terms follow the scene and the flags: more photons, a bigger photon map; more pixels, more
// frame bytes; a video, an encoder; and nothing is zero that the render holds.
TEST(MemoryPlan, TermsFollowTheSceneAndTheOutputs) {
    sl::SceneDesc scene = cornell_box();
    sl::RunOptions exr;
    exr.exr_dir = "frames";
    sl::RunOptions mp4 = exr;
    mp4.output = "out.mp4";
    const sl::MemoryBaseline a = sl::memory_baseline(scene, exr), v = sl::memory_baseline(scene, mp4);
    EXPECT_GT(a.program, 0u);
    EXPECT_GT(a.photon_map, 0u);
    EXPECT_GT(a.frames, 0u);
    EXPECT_EQ(a.encoder, 0u);
    EXPECT_GT(v.encoder, 0u);
    EXPECT_GT(a.records_per_path, 0.5);
    EXPECT_LT(a.records_per_path, scene.render.max_depth);
    scene.render.photons_per_pass *= 4;
    EXPECT_GT(sl::memory_baseline(scene, exr).photon_map, 3 * a.photon_map);
    scene.camera.width *= 2;
    EXPECT_GT(sl::memory_baseline(scene, exr).frames, a.frames);
}

// Two separate runs of `slowlight info SCENE --max-memory X` print the same K and figures.
TEST(MemoryPlan, InfoPicksTheSameKOnEveryRun) {
    ScratchDir dir;
    std::string lines[2];
    for (int run = 0; run < 2; ++run) {
        const std::string out = dir.file("info" + std::to_string(run) + ".txt");
        ProgramResult r = run_program({"info", sample("cornell_box.json"), "--frames", "96", "--max-memory", "100M"}, out);
        SL_EXPECT_EXIT(r, 0);
        const std::string text = read_text(out);
        std::smatch m;
        ASSERT_TRUE(std::regex_search(text, m, std::regex(R"(with --max-memory[^\n]*)"))) << text;
        lines[run] = m.str();
        EXPECT_NE(lines[run].find("K = "), std::string::npos) << lines[run];
    }
    EXPECT_EQ(lines[0], lines[1]);
}
