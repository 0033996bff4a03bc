#include "stages/output/hdf5_cube.h"

#include <cstddef>

#include "core/plugin.h"
#include "foundation/constants.h"
#include "foundation/errors.h"
#include "stages/output/atomic_file.h"

namespace sl {
namespace {

// The plugin's entry points (plugins/hdf5_writer/hdf5_writer.cpp), in load order.
struct Hdf5Api {
    void* (*create)(const char*, const char*, int, int, int, char*, size_t) = nullptr;
    int (*write_frame)(void*, int, const float*, char*, size_t) = nullptr;
    int (*write_dataset)(void*, const char*, int, const uint64_t*, const void*, int, char*, size_t) = nullptr;
    int (*text_attribute)(void*, const char*, const char*, const char*, char*, size_t) = nullptr;
    int (*number_attribute)(void*, const char*, const char*, double, char*, size_t) = nullptr;
    int (*integer_attribute)(void*, const char*, const char*, uint64_t, char*, size_t) = nullptr;
    int (*close)(void*, int) = nullptr;
    std::string error;
};

const Hdf5Api& hdf5() {
    static const Hdf5Api api = [] {
        const Plugin p = load_plugin("libslowlight_hdf5.so", "the HDF5 writer",
                                     {"slowlight_hdf5_create", "slowlight_hdf5_write_frame", "slowlight_hdf5_write_dataset",
                                      "slowlight_hdf5_text_attribute", "slowlight_hdf5_number_attribute",
                                      "slowlight_hdf5_integer_attribute", "slowlight_hdf5_close"});
        Hdf5Api a;
        a.error = p.error;
        if (!p.error.empty()) return a;
        a.create = p.function<decltype(a.create)>(0);
        a.write_frame = p.function<decltype(a.write_frame)>(1);
        a.write_dataset = p.function<decltype(a.write_dataset)>(2);
        a.text_attribute = p.function<decltype(a.text_attribute)>(3);
        a.number_attribute = p.function<decltype(a.number_attribute)>(4);
        a.integer_attribute = p.function<decltype(a.integer_attribute)>(5);
        a.close = p.function<decltype(a.close)>(6);
        return a;
    }();
    return api;
}

}  // namespace

Hdf5CubeWriter::Hdf5CubeWriter(const std::string& path, const Timeline& timeline, int height, int width)
    : path_(path), temp_(temp_sibling(path)), timeline_(timeline), height_(height), width_(width) {
    const Hdf5Api& api = hdf5();
    if (!api.error.empty()) throw RuntimeFailure("--hdf5 " + path + ": " + api.error);
    char error[256] = {};
    file_ = api.create(temp_.c_str(), "H", timeline.frames, height, width, error, sizeof error);
    if (!file_) {
        discard_file(temp_);
        throw RuntimeFailure("--hdf5 " + path + ": " + error);
    }
}

Hdf5CubeWriter::~Hdf5CubeWriter() {
    if (file_) {
        hdf5().close(file_, 0);
        discard_file(temp_);
    }
}

void Hdf5CubeWriter::fail(const std::string& what) {
    if (file_) hdf5().close(file_, 0);
    file_ = nullptr;
    discard_file(temp_);
    throw RuntimeFailure("--hdf5 " + path_ + ": " + what);
}

void Hdf5CubeWriter::image_dataset(const char* name, const float* rgb) {
    if (!file_) throw RuntimeFailure("--hdf5 " + path_ + ": closed");
    const uint64_t dims[3] = {uint64_t(height_), uint64_t(width_), 3};
    char error[256] = {};
    if (!hdf5().write_dataset(file_, name, 3, dims, rgb, 0, error, sizeof error)) fail(error);
}

void Hdf5CubeWriter::write_before(const float* rgb) { image_dataset("H_before", rgb); }
void Hdf5CubeWriter::write_after(const float* rgb) { image_dataset("H_after", rgb); }

void Hdf5CubeWriter::write_bin(int k, const float* rgb) {
    if (!file_ || k != bins_ || k >= timeline_.frames)
        throw RuntimeFailure("--hdf5 " + path_ + ": bin " + std::to_string(k) + " out of order");
    char error[256] = {};
    if (!hdf5().write_frame(file_, k, rgb, error, sizeof error)) fail(error);
    ++bins_;
}

void Hdf5CubeWriter::finish(const std::map<std::string, std::string>& text, const std::map<std::string, double>& numbers,
                            const std::map<std::string, uint64_t>& integers) {
    if (!file_) return;
    if (!complete()) throw RuntimeFailure("--hdf5 " + path_ + ": incomplete");
    const Hdf5Api& api = hdf5();
    char error[256] = {};
    auto check = [&](int ok) {
        if (!ok) fail(error);
    };
    const double t_start = kSpeedOfLight * timeline_.start_ns, delta_t = kSpeedOfLight * timeline_.delta();
    check(api.write_dataset(file_, "t_start", 0, nullptr, &t_start, 1, error, sizeof error));
    check(api.write_dataset(file_, "delta_t", 0, nullptr, &delta_t, 1, error, sizeof error));
    const uint64_t n = static_cast<uint64_t>(timeline_.frames) + 1;
    std::vector<double> edges(n);
    for (uint64_t k = 0; k < n; ++k) edges[k] = timeline_.edge(static_cast<int64_t>(k));
    check(api.write_dataset(file_, "frame_edges_ns", 1, &n, edges.data(), 1, error, sizeof error));
    check(api.text_attribute(file_, "H", "axes", "time, row (top first), column, channel (R, G, B)", error, sizeof error));
    check(api.text_attribute(file_, "H", "units", "radiance W sr^-1 m^-2 arriving within each bin", error, sizeof error));
    check(api.text_attribute(file_, "/", "t_units", "t_start and delta_t: metres of optical path (c * time)", error,
                             sizeof error));
    for (const auto& [k, v] : text) check(api.text_attribute(file_, "/", k.c_str(), v.c_str(), error, sizeof error));
    for (const auto& [k, v] : numbers) check(api.number_attribute(file_, "/", k.c_str(), v, error, sizeof error));
    for (const auto& [k, v] : integers) check(api.integer_attribute(file_, "/", k.c_str(), v, error, sizeof error));
    const bool flushed = api.close(file_, 1);
    file_ = nullptr;
    if (!flushed) {
        discard_file(temp_);
        throw RuntimeFailure("--hdf5 " + path_ + ": cannot write");
    }
    commit_file(temp_, path_);
}

}  // namespace sl
