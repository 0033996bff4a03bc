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

// The frames' bins in mitransient's order, (height, width, time, 3) float32: each pixel's time
// series is contiguous, so planes arriving one at a time are transposed on their way to disk.
// Up to `buffer_bytes` of planes (at least one) are kept, then transposed in blocks of pixels
// and written as one run per pixel (pwrite; one write per block when every plane fitted), into
// a file sized up front; renamed into place when the last plane is in.
class NpyTimeInnerWriter {
public:
    NpyTimeInnerWriter(const std::string& path, int times, int height, int width,
                       size_t buffer_bytes = size_t(64) << 20);  // RuntimeFailure
    ~NpyTimeInnerWriter();
    void append(const float* rgb);  // the next time's plane of height*width*3 values
    void finish();
    int planes_written() const { return written_; }

private:
    void flush();

    std::string path_, temp_;
    int fd_ = -1;
    int times_, written_ = 0, buffered_ = 0, first_buffered_ = 0, capacity_;
    size_t pixels_;
    uint64_t data_offset_;
    std::vector<float> buffer_;  // the buffered planes, as they came: plane t at t * pixels_ * 3
};

struct NpyCube {
    int planes = 0, height = 0, width = 0;
    std::vector<float> data;  // planes * height * width * 3
    const float* plane(int k) const { return data.data() + static_cast<size_t>(k) * height * width * 3; }
};

// Reads a float32 (planes, height, width, 3) .npy. Throws InputError on a malformed file.
NpyCube read_npy_cube(const std::string& path);

}  // namespace sl
