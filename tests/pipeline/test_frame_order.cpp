// Frames reach the writers in index order, whatever the timing: a serial oneTBB node may start
// its next body before it hands on its last output, so without the pipeline's sequencers a
// fast frame (or a section that returns at once) can overtake the one before it. These tests
// make that race likely (many tiny frames, random delays injected into assembly, more threads
// than cores, many sections with two alive, sections read back instantly by --resume) and check
// the order every stream sees: the frames, the cube's planes, the video.
#include <gtest/gtest.h>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "config/parse_scene.h"
#include "pipeline/frames_in_memory.h"
#include "pipeline/render_pipeline.h"
#include "tests/common/video_reader.h"
#include "tests/pipeline/pipeline_helpers.h"

namespace sl::test {
namespace {

// Records the order in which the write stage hands frames and cube planes to a sink.
class OrderRecorder : public FrameSink {
public:
    std::vector<int> frames;     // write_frame's indices, in call order
    std::vector<int> plane_after; // for each cube plane: the last frame index written before it
    int steady_before = -1;       // how many frames had been written when the steady image came
    bool wants_cube() const override { return true; }
    void write_frame(int index, const std::vector<float>&, bool, const Metadata&) override { frames.push_back(index); }
    void write_steady(const std::vector<float>&, const Metadata&) override {
        steady_before = static_cast<int>(frames.size());
    }
    void write_cube_plane(const std::vector<float>&) override {
        plane_after.push_back(frames.empty() ? -1 : frames.back());
    }
};

SceneDesc tiny_scene(int frames) {
    SceneDesc scene = parse_scene_file(sample("cornell_box.json"));
    scene.camera.width = 2;
    scene.camera.height = 2;
    scene.time.frames = frames;
    scene.render.passes = 1;
    scene.render.photons_per_pass = 300;
    return scene;
}

// Runs the pipeline on `threads` worker threads (more than the machine's cores: preemption
// between a body's end and its hand-over is what lets a frame overtake), with a random delay of
// up to 50 µs after one frame in three is assembled.
OrderRecorder run_with_delays(const RenderContext& ctx, int sections, bool overlap, int threads, unsigned seed) {
    tbb::global_control more_threads(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
    tbb::task_arena arena(threads);
    OrderRecorder sink;
    PipelineJob job;
    job.ctx = &ctx;
    job.plan.sections = sections;
    job.plan.overlap = overlap;
    job.check_black = false;
    job.log = [](const std::string&) {};
    std::mt19937 rng(seed);
    std::vector<int> delay_us(static_cast<size_t>(ctx.timeline.frames));
    for (int& d : delay_us) d = rng() % 3 == 0 ? static_cast<int>(rng() % 50) : 0;
    job.frame_assembled = [&](int frame) {
        if (delay_us[static_cast<size_t>(frame)] > 0)
            std::this_thread::sleep_for(std::chrono::microseconds(delay_us[static_cast<size_t>(frame)]));
    };
    std::atomic<bool> never{false};
    arena.execute([&] { run_pipeline(job, sink, {}, never); });
    return sink;
}

void expect_in_order(const OrderRecorder& sink, int frames) {
    ASSERT_EQ(static_cast<int>(sink.frames.size()), frames);
    int misplaced = 0, first_bad = -1;
    for (int k = 0; k < frames; ++k)
        if (sink.frames[static_cast<size_t>(k)] != k && misplaced++ == 0) first_bad = k;
    EXPECT_EQ(misplaced, 0) << "first frame out of order at position " << first_bad << ": got frame "
                            << (first_bad >= 0 ? sink.frames[static_cast<size_t>(first_bad)] : -1);
    // The cube: the plane before start_ns after frame 0, one bucket per frame, the plane after
    // end_ns after the last frame.
    ASSERT_EQ(static_cast<int>(sink.plane_after.size()), frames + 2);
    EXPECT_EQ(sink.plane_after[0], 0);
    for (int k = 0; k < frames; ++k) EXPECT_EQ(sink.plane_after[static_cast<size_t>(k) + 1], k) << "plane " << k + 1;
    EXPECT_EQ(sink.plane_after.back(), frames - 1);
}

TEST(FrameOrder, ManyTinyFramesWithDelaysInAssemblyArriveInOrder) {
    const int frames = 3000;
    RenderContext ctx(tiny_scene(frames));
    for (unsigned seed = 1; seed <= 3; ++seed) {
        OrderRecorder sink = run_with_delays(ctx, 1, false, 6, seed);
        expect_in_order(sink, frames);
        EXPECT_EQ(sink.steady_before, 0);  // the steady image (and the exposure) before any frame
    }
}

TEST(FrameOrder, ManySectionsTwoAliveArriveInOrder) {
    const int frames = 600;
    RenderContext ctx(tiny_scene(frames));
    for (unsigned seed = 1; seed <= 2; ++seed) {
        OrderRecorder sink = run_with_delays(ctx, 120, true, 6, seed);
        expect_in_order(sink, frames);
    }
}

// Sections read back by --resume return from the render stage at once, between sections that
// render: the resumed run's video shows the uninterrupted run's frames in the same order (--cube
// needs every section rendered, so it never resumes).
TEST(FrameOrder, SectionsResumedInstantlyKeepTheVideoInOrder) {
    ScratchDir dir;
    const int frames = 40, sections = 20;
    auto args = [&](const std::string& name) {
        return small_render("", {"--sections", std::to_string(sections), "--exr-dir", dir.file(name), "-o",
                                 dir.file(name + ".mkv"), "--threads", "4"},
                            frames, 1, 500);
    };
    // Two renders of the same settings into two folders; then every other section's frames are
    // removed from the second, and --resume renders only those, reading the rest back.
    ProgramResult a = run_program(args("a"));
    ASSERT_EQ(a.exit_code, 0) << a.err;
    ProgramResult b = run_program(args("b"));
    ASSERT_EQ(b.exit_code, 0) << b.err;
    for (int s = 0; s < sections; s += 2)
        std::filesystem::remove(dir.file("b") + "/" + frame_name(s * frames / sections));
    std::vector<std::string> resume = args("b");
    resume.push_back("--resume");
    ProgramResult r = run_program(resume);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // Lossless FFV1 of bit-identical frames: the decoded frames match one for one, in order.
    const VideoInfo fresh = read_video(dir.file("a.mkv")), resumed = read_video(dir.file("b.mkv"));
    ASSERT_EQ(resumed.frames, frames);
    EXPECT_EQ(fresh.mean_luma, resumed.mean_luma) << "the resumed video's frames differ or are out of order";
}

}  // namespace
}  // namespace sl::test
