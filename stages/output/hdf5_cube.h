#pragma once
// The frames' bins as an HDF5 file in the layout of the tal toolkit (time first, its time axis
// t_start and delta_t in metres of optical path), written through libhdf5 (in a plugin,
// plugins/hdf5_writer/, loaded on first use) one bin at a time as frames leave the pipeline: a
// chunked dataset of one bin per chunk, each bin a hyperslab, so the whole cube is never in
// memory. Written to a temporary name, renamed when complete.
//   /H              float32 (frames, height, width, 3): bin k = radiance arriving in frame k
//   /H_before, /H_after  float32 (height, width, 3): what arrived before start_ns / at or after end_ns
//   /t_start, /delta_t   float64 scalars, metres (c · start_ns, c · Δ)
//   /frame_edges_ns      float64 (frames + 1)
//   attributes on / : strings, numbers and integers given to finish() (scene, seed, exposure, ...)
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "foundation/timeline.h"

namespace sl {

class Hdf5CubeWriter {
public:
    Hdf5CubeWriter(const std::string& path, const Timeline& timeline, int height, int width);  // RuntimeFailure
    ~Hdf5CubeWriter();  // an unfinished file is removed
    Hdf5CubeWriter(const Hdf5CubeWriter&) = delete;
    Hdf5CubeWriter& operator=(const Hdf5CubeWriter&) = delete;

    void write_before(const float* rgb);
    void write_bin(int k, const float* rgb);  // in order, k = 0 .. frames - 1
    void write_after(const float* rgb);
    bool complete() const { return bins_ == timeline_.frames; }
    void finish(const std::map<std::string, std::string>& text, const std::map<std::string, double>& numbers,
                const std::map<std::string, uint64_t>& integers);

private:
    void image_dataset(const char* name, const float* rgb);
    [[noreturn]] void fail(const std::string& what);  // closes, removes the temporary, throws

    std::string path_, temp_;
    Timeline timeline_;
    int height_, width_, bins_ = 0;
    void* file_ = nullptr;  // the plugin's handle
};

}  // namespace sl
