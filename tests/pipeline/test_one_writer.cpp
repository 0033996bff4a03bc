// Only the write stage touches the outputs. The program once wrote the steady image from the
// assemble stage while the write stage was tone-mapping a frame into the same scratch buffer
// (a race seen in 3 of 3 runs with two sections alive). Here a sink that lingers in every
// write call (so any two calls from different stages would overlap) counts overlapping calls,
// with three sections alive at once, the exposure preview, the steady image and the cube:
// there must be none, and every frame must arrive once and in order.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "config/parse_scene.h"
#include "pipeline/frame_sink.h"
#include "pipeline/render_pipeline.h"
#include "stages/render/render_context.h"
#include "tests/pipeline/pipeline_helpers.h"

namespace sl::test {
namespace {

class LingeringSink : public FrameSink {
public:
    bool needs_exposure() const override { return true; }
    void set_exposure_plan(const ExposurePlan& p) override {
        Inside in(*this);
        exposure_ = p.base;
    }
    std::optional<double> exposure() const override { return exposure_; }
    bool wants_cube() const override { return true; }
    void write_frame(int index, const std::vector<float>&, bool, const Metadata&) override {
        Inside in(*this);
        order.push_back(index);
    }
    void write_steady(const std::vector<float>&, const Metadata&) override {
        Inside in(*this);
        ++steady;
    }
    void write_cube_plane(const std::vector<float>&) override {
        Inside in(*this);
        ++planes;
    }

    std::atomic<int> overlaps{0};
    std::vector<int> order;
    int steady = 0, planes = 0;

private:
    struct Inside {
        explicit Inside(LingeringSink& s) : s_(s) {
            if (s_.busy_.fetch_add(1) != 0) ++s_.overlaps;
            std::this_thread::sleep_for(std::chrono::milliseconds(3));  // widen any window
        }
        ~Inside() { s_.busy_.fetch_sub(1); }
        LingeringSink& s_;
    };
    std::atomic<int> busy_{0};
    std::optional<double> exposure_;
};

TEST(OneWriter, OutputsAreTouchedByOneStageAtATimeWithSectionsAlive) {
    SceneDesc scene = parse_scene_file(sample("cornell_box.json"));
    scene.camera.width = scene.camera.height = 24;
    scene.time.frames = 12;
    scene.render.passes = 3;
    scene.render.photons_per_pass = 3000;
    RenderContext ctx(scene);
    PipelineJob job;
    job.ctx = &ctx;
    job.plan.sections = 3;
    job.plan.overlap = true;  // the next section renders and assembles while this one is written
    job.log = [](const std::string&) {};
    LingeringSink sink;
    std::atomic<bool> never{false};
    run_pipeline(job, sink, {}, never);

    EXPECT_EQ(sink.overlaps.load(), 0);
    std::vector<int> want(12);
    for (int k = 0; k < 12; ++k) want[k] = k;
    EXPECT_EQ(sink.order, want);
    EXPECT_EQ(sink.steady, 1);
    EXPECT_EQ(sink.planes, 12 + 2);  // before, every bucket, after
    ASSERT_TRUE(sink.exposure().has_value());
    EXPECT_GT(*sink.exposure(), 0.0);
}

}  // namespace
}  // namespace sl::test
