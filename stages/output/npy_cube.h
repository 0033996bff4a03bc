#pragma once
// The transient cube as a NumPy .npy file: float32, C order, shape (planes, height, width, 3).
// Planes are written one at a time, as frames leave the pipeline, to a temporary name that is
// renamed into place when the last plane is in.
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace sl {

class NpyCubeWriter {
public:
    NpyCubeWriter(const std::string& path, int planes, int height, int width);  // RuntimeFailure
    ~NpyCubeWriter();  // an unfinished cube is removed, never left looking whole
    void append(const float* rgb);  // one plane of height*width*3 values
    void finish();                  // every plane must have been appended
    int planes_written() const { return written_; }

private:
    std::string path_, temp_;
    std::FILE* file_ = nullptr;
    int planes_, written_ = 0;
    size_t plane_values_;
};

struct NpyCube {
    int planes = 0, height = 0, width = 0;
    std::vector<float> data;  // planes * height * width * 3
    const float* plane(int k) const { return data.data() + static_cast<size_t>(k) * height * width * 3; }
};

// Reads a float32 (planes, height, width, 3) .npy. Throws InputError on a malformed file.
NpyCube read_npy_cube(const std::string& path);

}  // namespace sl
