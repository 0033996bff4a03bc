#include "stages/output/hdf5_cube.h"

#include <hdf5.h>

#include "foundation/constants.h"
#include "foundation/errors.h"
#include "stages/output/atomic_file.h"

namespace sl {
namespace {

// libhdf5 prints its error stack on stderr by default; failures here become one error: line.
void silence_hdf5() {
    static const bool once = [] {
        H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
        return true;
    }();
    (void)once;
}

// Dataset creation properties without modification times: the same render makes the same bytes
// (one process or many ranks alike).
hid_t untimed() {
    hid_t props = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_obj_track_times(props, 0);
    return props;
}

hid_t create_dataset(hid_t file, const char* name, hid_t type, hid_t space) {
    hid_t props = untimed();
    hid_t ds = H5Dcreate2(file, name, type, space, H5P_DEFAULT, props, H5P_DEFAULT);
    H5Pclose(props);
    return ds;
}

void scalar(hid_t file, const char* name, double v) {
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t ds = create_dataset(file, name, H5T_IEEE_F64LE, space);
    herr_t ok = ds < 0 ? -1 : H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v);
    if (ds >= 0) H5Dclose(ds);
    H5Sclose(space);
    if (ok < 0) throw RuntimeFailure(std::string("cannot write ") + name);
}

void text_attribute(hid_t obj, const std::string& name, const std::string& value) {
    // Variable-length UTF-8, as h5py writes strings (and reads them back as str).
    hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    H5Tset_cset(type, H5T_CSET_UTF8);
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
    const char* text = value.c_str();
    herr_t ok = a < 0 ? -1 : H5Awrite(a, type, &text);
    if (a >= 0) H5Aclose(a);
    H5Sclose(space);
    H5Tclose(type);
    if (ok < 0) throw RuntimeFailure("cannot write the attribute " + name);
}

void number_attribute(hid_t obj, const std::string& name, double v) {
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(obj, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT);
    herr_t ok = a < 0 ? -1 : H5Awrite(a, H5T_NATIVE_DOUBLE, &v);
    if (a >= 0) H5Aclose(a);
    H5Sclose(space);
    if (ok < 0) throw RuntimeFailure("cannot write the attribute " + name);
}

void integer_attribute(hid_t obj, const std::string& name, uint64_t v) {
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(obj, name.c_str(), H5T_STD_U64LE, space, H5P_DEFAULT, H5P_DEFAULT);
    herr_t ok = a < 0 ? -1 : H5Awrite(a, H5T_NATIVE_UINT64, &v);
    if (a >= 0) H5Aclose(a);
    H5Sclose(space);
    if (ok < 0) throw RuntimeFailure("cannot write the attribute " + name);
}

}  // namespace

Hdf5CubeWriter::Hdf5CubeWriter(const std::string& path, const Timeline& timeline, int height, int width)
    : path_(path), temp_(temp_sibling(path)), timeline_(timeline), height_(height), width_(width) {
    silence_hdf5();
    file_ = H5Fcreate(temp_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (file_ < 0) {
        discard_file(temp_);
        throw RuntimeFailure("--hdf5 " + path + ": cannot create the file");
    }
    const hsize_t dims[4] = {static_cast<hsize_t>(timeline.frames), static_cast<hsize_t>(height),
                             static_cast<hsize_t>(width), 3};
    const hsize_t chunk[4] = {1, static_cast<hsize_t>(height), static_cast<hsize_t>(width), 3};  // one bin
    hid_t space = H5Screate_simple(4, dims, nullptr);
    hid_t props = untimed();
    H5Pset_chunk(props, 4, chunk);
    data_ = H5Dcreate2(file_, "H", H5T_IEEE_F32LE, space, H5P_DEFAULT, props, H5P_DEFAULT);
    H5Pclose(props);
    H5Sclose(space);
    if (data_ < 0) {
        close();
        discard_file(temp_);
        throw RuntimeFailure("--hdf5 " + path + ": cannot create the dataset H");
    }
}

Hdf5CubeWriter::~Hdf5CubeWriter() {
    if (file_ >= 0) {
        close();
        discard_file(temp_);
    }
}

void Hdf5CubeWriter::close() noexcept {
    if (data_ >= 0) H5Dclose(data_);
    if (file_ >= 0) H5Fclose(file_);
    data_ = file_ = -1;
}

void Hdf5CubeWriter::image_dataset(const char* name, const float* rgb) {
    if (file_ < 0) throw RuntimeFailure("--hdf5 " + path_ + ": closed");
    const hsize_t dims[3] = {static_cast<hsize_t>(height_), static_cast<hsize_t>(width_), 3};
    hid_t space = H5Screate_simple(3, dims, nullptr);
    hid_t ds = create_dataset(file_, name, H5T_IEEE_F32LE, space);
    herr_t ok = ds < 0 ? -1 : H5Dwrite(ds, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, rgb);
    if (ds >= 0) H5Dclose(ds);
    H5Sclose(space);
    if (ok < 0) throw RuntimeFailure("--hdf5 " + path_ + ": cannot write " + name);
}

void Hdf5CubeWriter::write_before(const float* rgb) { image_dataset("H_before", rgb); }
void Hdf5CubeWriter::write_after(const float* rgb) { image_dataset("H_after", rgb); }

void Hdf5CubeWriter::write_bin(int k, const float* rgb) {
    if (file_ < 0 || k != bins_ || k >= timeline_.frames)
        throw RuntimeFailure("--hdf5 " + path_ + ": bin " + std::to_string(k) + " out of order");
    const hsize_t start[4] = {static_cast<hsize_t>(k), 0, 0, 0};
    const hsize_t count[4] = {1, static_cast<hsize_t>(height_), static_cast<hsize_t>(width_), 3};
    hid_t file_space = H5Dget_space(data_);
    H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start, nullptr, count, nullptr);
    hid_t mem_space = H5Screate_simple(4, count, nullptr);
    herr_t ok = H5Dwrite(data_, H5T_NATIVE_FLOAT, mem_space, file_space, H5P_DEFAULT, rgb);
    H5Sclose(mem_space);
    H5Sclose(file_space);
    if (ok < 0) throw RuntimeFailure("--hdf5 " + path_ + ": cannot write bin " + std::to_string(k));
    ++bins_;
}

void Hdf5CubeWriter::finish(const std::map<std::string, std::string>& text, const std::map<std::string, double>& numbers,
                            const std::map<std::string, uint64_t>& integers) {
    if (file_ < 0) return;
    if (!complete()) throw RuntimeFailure("--hdf5 " + path_ + ": incomplete");
    try {
        scalar(file_, "t_start", kSpeedOfLight * timeline_.start_ns);
        scalar(file_, "delta_t", kSpeedOfLight * timeline_.delta());
        const hsize_t n = static_cast<hsize_t>(timeline_.frames) + 1;
        std::vector<double> edges(n);
        for (hsize_t k = 0; k < n; ++k) edges[k] = timeline_.edge(static_cast<int64_t>(k));
        hid_t space = H5Screate_simple(1, &n, nullptr);
        hid_t ds = create_dataset(file_, "frame_edges_ns", H5T_IEEE_F64LE, space);
        herr_t ok = ds < 0 ? -1 : H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, edges.data());
        if (ds >= 0) H5Dclose(ds);
        H5Sclose(space);
        if (ok < 0) throw RuntimeFailure("cannot write frame_edges_ns");
        text_attribute(data_, "axes", "time, row (top first), column, channel (R, G, B)");
        text_attribute(data_, "units", "radiance W sr^-1 m^-2 arriving within each bin");
        hid_t root = H5Gopen2(file_, "/", H5P_DEFAULT);
        try {
            text_attribute(root, "t_units", "t_start and delta_t: metres of optical path (c * time)");
            for (const auto& [k, v] : text) text_attribute(root, k, v);
            for (const auto& [k, v] : numbers) number_attribute(root, k, v);
            for (const auto& [k, v] : integers) integer_attribute(root, k, v);
        } catch (...) {
            H5Gclose(root);
            throw;
        }
        H5Gclose(root);
    } catch (const RuntimeFailure& e) {
        throw RuntimeFailure("--hdf5 " + path_ + ": " + e.what());
    }
    const bool flushed = H5Fflush(file_, H5F_SCOPE_GLOBAL) >= 0;
    close();
    if (!flushed) {
        discard_file(temp_);
        throw RuntimeFailure("--hdf5 " + path_ + ": cannot write");
    }
    commit_file(temp_, path_);
}

}  // namespace sl
