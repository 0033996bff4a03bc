// With constant light, a section after the first starts from the last frame of the section
// before it (carried, not gathered again). When --resume renders such a section afresh while the
// section before it is only on disk (its EXR frames in --exr-dir, nothing in memory, no
// checkpoint), the carried frame is read back from that section's last EXR: the result must be
// the very render that never stopped, and the video must still hold every frame.
#include <gtest/gtest.h>

#include <filesystem>

#include "checkpoint_helpers.h"
#include "tests/common/video_reader.h"

namespace sl {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> three_sections(const std::string& dir, const std::string& sub) {
    return test::render_into(dir, sub, {"--width", "40", "--height", "30", "--frames", "6", "--passes", "6",
                                        "--photons", "8000", "--sections", "3"});
}

TEST(CarriedSections, ResumedFromTheFramesOnDiskGivesTheSameRender) {
    const std::string dir = test::fresh_dir("carried");
    test::RunResult ref = test::run(three_sections(dir, "ref"), dir);
    ASSERT_EQ(ref.status, 0) << ref.err;
    test::RunResult cut = test::run(three_sections(dir, "cut"), dir);
    ASSERT_EQ(cut.status, 0) << cut.err;
    // The last section is lost (as if the machine stopped just after the second one was
    // written): its last frame and steady.exr are gone, so --resume must render it again.
    fs::remove(dir + "/cut" + test::frame_name(5));
    fs::remove(dir + "/cut/steady.exr");
    fs::remove(dir + "/cut.mkv");
    test::RunResult resumed = test::run(test::with(three_sections(dir, "cut"), {"--resume"}), dir);
    ASSERT_EQ(resumed.status, 0) << resumed.err;
    EXPECT_NE(resumed.err.find("section 3/3"), std::string::npos) << resumed.err;
    EXPECT_EQ(resumed.err.find("section 1/3"), std::string::npos) << "only the lost section is rendered:\n" << resumed.err;
    test::expect_same_exrs(dir + "/cut", dir + "/ref", 6);
    VideoInfo a = read_video(dir + "/cut.mkv"), b = read_video(dir + "/ref.mkv");
    EXPECT_EQ(a.frames, 6);
    EXPECT_EQ(a.mean_luma, b.mean_luma);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace sl
