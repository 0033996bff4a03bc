// mitransient's order, (height, width, time, 3): planes written one at a time come out
// transposed, whether every plane fits the writer's buffer or it flushes several times.
#include <gtest/gtest.h>

#include <filesystem>

#include "stages/output/npy_cube.h"
#include "tests/common/temp_dir.h"

namespace sl {
namespace {

TEST(NpyTimeInner, PlanesComeOutTransposedWhateverTheBuffer) {
    test::TempDir dir("sl_npy_time_inner");
    const int times = 7, height = 5, width = 300;  // more pixels than one block of the transpose
    const size_t plane_values = size_t(height) * width * 3;
    auto value = [](int t, size_t i) { return static_cast<float>(t * 1000003 + i); };  // distinct, exact (< 2^24)
    for (size_t planes_in_buffer : {size_t(1), size_t(3), size_t(7), size_t(100)}) {
        const std::string path = dir.file("m" + std::to_string(planes_in_buffer) + ".npy");
        {
            NpyTimeInnerWriter w(path, times, height, width, planes_in_buffer * plane_values * sizeof(float));
            std::vector<float> plane(plane_values);
            for (int t = 0; t < times; ++t) {
                for (size_t i = 0; i < plane_values; ++i) plane[i] = value(t, i);
                w.append(plane.data());
            }
            w.finish();
        }
        // Read back as (planes, height, width, 3) = (height, width, times, 3): [y][x][t][c].
        NpyCube c = read_npy_cube(path);
        ASSERT_EQ(c.planes, height);
        ASSERT_EQ(c.height, width);
        ASSERT_EQ(c.width, times);
        size_t wrong = 0;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                for (int t = 0; t < times; ++t)
                    for (int ch = 0; ch < 3; ++ch) {
                        const size_t at = ((size_t(y) * width + x) * times + t) * 3 + ch;
                        const size_t i = (size_t(y) * width + x) * 3 + ch;
                        wrong += c.data[at] != value(t, i);
                    }
        EXPECT_EQ(wrong, 0u) << planes_in_buffer << " planes in the buffer";
    }
}

TEST(NpyTimeInner, AnUnfinishedCubeLeavesNoFile) {
    test::TempDir dir("sl_npy_time_inner_cut");
    const std::string path = dir.file("cut.npy");
    {
        NpyTimeInnerWriter w(path, 4, 2, 2);
        std::vector<float> plane(12, 1.0f);
        w.append(plane.data());
    }
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace sl
