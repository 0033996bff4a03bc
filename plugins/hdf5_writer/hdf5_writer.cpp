// The HDF5 writer (--hdf5), a plugin loaded only when an HDF5 file is asked for: libhdf5 and
// what Debian builds it with (libcurl, libsz, libaec, ...) would cost every render a few MiB of
// resident memory. A C interface over libhdf5's own: a file with one chunked 4-D float dataset
// written one hyperslab at a time, plus datasets and attributes; stages/output/hdf5_cube.cpp
// decides names, order and the temporary file.
#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#define SL_EXPORT extern "C" __attribute__((visibility("default")))

namespace {

struct File {
    hid_t file = -1, data = -1;  // the file and its 4-D dataset
};

void copy_error(const std::string& why, char* error, size_t size) {
    if (size == 0) return;
    std::strncpy(error, why.c_str(), size - 1);
    error[size - 1] = '\0';
}

// Dataset creation properties without modification times: the same writes make the same bytes.
hid_t untimed() {
    hid_t props = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_obj_track_times(props, 0);
    return props;
}

hid_t object(const File& f, const char* name) {
    return std::strcmp(name, "/") == 0 ? H5Gopen2(f.file, "/", H5P_DEFAULT) : H5Dopen2(f.file, name, H5P_DEFAULT);
}

void close_object(hid_t obj) {
    if (obj < 0) return;
    if (H5Iget_type(obj) == H5I_GROUP) H5Gclose(obj);
    else H5Dclose(obj);
}

// An attribute of any type on `target` ("/" or a dataset's name); `value` points to its bytes.
int attribute(File* f, const char* target, const char* name, hid_t file_type, hid_t mem_type, const void* value,
              char* error, size_t size) {
    hid_t obj = object(*f, target);
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t a = obj < 0 ? -1 : H5Acreate2(obj, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT);
    const herr_t ok = a < 0 ? -1 : H5Awrite(a, mem_type, value);
    if (a >= 0) H5Aclose(a);
    H5Sclose(space);
    close_object(obj);
    if (ok < 0) copy_error(std::string("cannot write the attribute ") + name, error, size);
    return ok >= 0;
}

}  // namespace

// Creates `path` with the dataset `name` of shape (frames, height, width, 3), float32, chunked
// one frame per chunk. Returns a handle, or null with a message. libhdf5 prints nothing itself.
SL_EXPORT void* slowlight_hdf5_create(const char* path, const char* name, int frames, int height, int width,
                                      char* error, size_t size) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    File* f = new File;
    f->file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (f->file < 0) {
        copy_error("cannot create the file", error, size);
        delete f;
        return nullptr;
    }
    const hsize_t dims[4] = {hsize_t(frames), hsize_t(height), hsize_t(width), 3};
    const hsize_t chunk[4] = {1, hsize_t(height), hsize_t(width), 3};
    hid_t space = H5Screate_simple(4, dims, nullptr);
    hid_t props = untimed();
    H5Pset_chunk(props, 4, chunk);
    f->data = H5Dcreate2(f->file, name, H5T_IEEE_F32LE, space, H5P_DEFAULT, props, H5P_DEFAULT);
    H5Pclose(props);
    H5Sclose(space);
    if (f->data < 0) {
        copy_error(std::string("cannot create the dataset ") + name, error, size);
        H5Fclose(f->file);
        delete f;
        return nullptr;
    }
    return f;
}

// Frame `k` of the 4-D dataset: height*width*3 floats.
SL_EXPORT int slowlight_hdf5_write_frame(void* handle, int k, const float* rgb, char* error, size_t size) {
    File* f = static_cast<File*>(handle);
    hid_t file_space = H5Dget_space(f->data);
    hsize_t dims[4];
    H5Sget_simple_extent_dims(file_space, dims, nullptr);
    const hsize_t start[4] = {hsize_t(k), 0, 0, 0}, count[4] = {1, dims[1], dims[2], 3};
    H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start, nullptr, count, nullptr);
    hid_t mem_space = H5Screate_simple(4, count, nullptr);
    const herr_t ok = H5Dwrite(f->data, H5T_NATIVE_FLOAT, mem_space, file_space, H5P_DEFAULT, rgb);
    H5Sclose(mem_space);
    H5Sclose(file_space);
    if (ok < 0) copy_error("cannot write frame " + std::to_string(k), error, size);
    return ok >= 0;
}

// A whole dataset of `rank` dimensions: float32 from floats (`is_double` 0) or float64 from doubles.
SL_EXPORT int slowlight_hdf5_write_dataset(void* handle, const char* name, int rank, const uint64_t* dims,
                                           const void* values, int is_double, char* error, size_t size) {
    File* f = static_cast<File*>(handle);
    hsize_t d[8];
    for (int i = 0; i < rank && i < 8; ++i) d[i] = dims[i];
    hid_t space = rank == 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(rank, d, nullptr);
    hid_t props = untimed();
    hid_t ds = H5Dcreate2(f->file, name, is_double ? H5T_IEEE_F64LE : H5T_IEEE_F32LE, space, H5P_DEFAULT, props,
                          H5P_DEFAULT);
    H5Pclose(props);
    const herr_t ok =
        ds < 0 ? -1 : H5Dwrite(ds, is_double ? H5T_NATIVE_DOUBLE : H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values);
    if (ds >= 0) H5Dclose(ds);
    H5Sclose(space);
    if (ok < 0) copy_error(std::string("cannot write ") + name, error, size);
    return ok >= 0;
}

// Attributes on "/" or a dataset: UTF-8 text (variable length, as h5py writes strings), float64, uint64.
SL_EXPORT int slowlight_hdf5_text_attribute(void* handle, const char* target, const char* name, const char* value,
                                            char* error, size_t size) {
    hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    H5Tset_cset(type, H5T_CSET_UTF8);
    const int ok = attribute(static_cast<File*>(handle), target, name, type, type, &value, error, size);
    H5Tclose(type);
    return ok;
}

SL_EXPORT int slowlight_hdf5_number_attribute(void* handle, const char* target, const char* name, double value,
                                              char* error, size_t size) {
    return attribute(static_cast<File*>(handle), target, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value, error, size);
}

SL_EXPORT int slowlight_hdf5_integer_attribute(void* handle, const char* target, const char* name, uint64_t value,
                                               char* error, size_t size) {
    return attribute(static_cast<File*>(handle), target, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, &value, error, size);
}

// Flushes (when `keep`) and closes the file; the handle is gone either way. Returns 0 when the
// flush failed.
SL_EXPORT int slowlight_hdf5_close(void* handle, int keep) {
    File* f = static_cast<File*>(handle);
    bool ok = !keep || H5Fflush(f->file, H5F_SCOPE_GLOBAL) >= 0;
    if (f->data >= 0) H5Dclose(f->data);
    ok = H5Fclose(f->file) >= 0 && ok;
    delete f;
    return ok;
}
