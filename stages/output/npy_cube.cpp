#include "stages/output/npy_cube.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>
#include <optional>
#include <regex>

#include "config/input_file.h"
#include "config/text_util.h"
#include "foundation/errors.h"
#include "stages/output/atomic_file.h"

namespace sl {
namespace {

std::string npy_header(int planes, int height, int width) {
    std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(planes) + ", " +
                       std::to_string(height) + ", " + std::to_string(width) + ", 3), }";
    // Magic (6) + version (2) + length (2) + dict + padding + '\n', a multiple of 64 bytes.
    size_t total = 10 + dict.size() + 1;
    dict.append((64 - total % 64) % 64, ' ');
    dict += '\n';
    std::string h("\x93NUMPY\x01\x00", 8);
    h += static_cast<char>(dict.size() & 0xff);
    h += static_cast<char>(dict.size() >> 8);
    return h + dict;
}

}  // namespace

NpyCubeWriter::NpyCubeWriter(const std::string& path, int planes, int height, int width)
    : path_(path), temp_(temp_sibling(path)), planes_(planes),
      plane_values_(static_cast<size_t>(height) * width * 3) {
    file_ = std::fopen(temp_.c_str(), "wb");
    if (!file_) throw RuntimeFailure("--cube " + path + ": cannot write: " + std::strerror(errno));
    std::string h = npy_header(planes, height, width);
    if (std::fwrite(h.data(), 1, h.size(), file_) != h.size()) {
        std::fclose(file_);
        file_ = nullptr;
        discard_file(temp_);
        throw RuntimeFailure("--cube " + path + ": cannot write");
    }
}

NpyCubeWriter::~NpyCubeWriter() {
    if (file_) {
        std::fclose(file_);
        discard_file(temp_);
    }
}

void NpyCubeWriter::append(const float* rgb) {
    if (!file_ || written_ >= planes_) throw RuntimeFailure("--cube " + path_ + ": too many planes");
    if (std::fwrite(rgb, sizeof(float), plane_values_, file_) != plane_values_)
        throw RuntimeFailure("--cube " + path_ + ": cannot write: " + std::strerror(errno));
    ++written_;
}

void NpyCubeWriter::finish() {
    if (!file_) return;
    if (written_ != planes_) throw RuntimeFailure("--cube " + path_ + ": incomplete");
    bool ok = std::fflush(file_) == 0;
    ok = (std::fclose(file_) == 0) && ok;
    file_ = nullptr;
    if (!ok) {
        discard_file(temp_);
        throw RuntimeFailure("--cube " + path_ + ": cannot write: " + std::strerror(errno));
    }
    commit_file(temp_, path_);
}

NpyTimeInnerWriter::NpyTimeInnerWriter(const std::string& path, int times, int height, int width, size_t buffer_bytes)
    : path_(path), temp_(temp_sibling(path)), times_(times), pixels_(static_cast<size_t>(height) * width) {
    const size_t plane_bytes = pixels_ * 3 * sizeof(float);
    capacity_ = static_cast<int>(std::clamp<size_t>(buffer_bytes / plane_bytes, 1, static_cast<size_t>(times)));
    const std::string h = npy_header(height, width, times);
    data_offset_ = h.size();
    fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    const uint64_t total = data_offset_ + static_cast<uint64_t>(plane_bytes) * times;
    if (fd_ < 0 || ::write(fd_, h.data(), h.size()) != static_cast<ssize_t>(h.size()) ||
        ::ftruncate(fd_, static_cast<off_t>(total)) != 0) {
        const std::string why = std::strerror(errno);
        if (fd_ >= 0) ::close(fd_);
        fd_ = -1;
        discard_file(temp_);
        throw RuntimeFailure("--cube " + path + ": cannot write: " + why);
    }
    buffer_.resize(pixels_ * 3 * static_cast<size_t>(capacity_));
}

NpyTimeInnerWriter::~NpyTimeInnerWriter() {
    if (fd_ >= 0) {
        ::close(fd_);
        discard_file(temp_);
    }
}

void NpyTimeInnerWriter::append(const float* rgb) {
    if (fd_ < 0 || written_ >= times_) throw RuntimeFailure("--cube " + path_ + ": too many planes");
    // Kept as it came (a plain copy); flush() transposes in blocks that stay in cache.
    std::memcpy(buffer_.data() + static_cast<size_t>(buffered_) * pixels_ * 3, rgb, pixels_ * 3 * sizeof(float));
    ++buffered_;
    ++written_;
    if (buffered_ == capacity_ || written_ == times_) flush();
}

void NpyTimeInnerWriter::flush() {
    // Pixels in blocks: each block's runs (its pixels' buffered times, contiguous in the file per
    // pixel) are gathered from the planes into `runs`, then written one pwrite per pixel, or one
    // for the whole block when the buffered times are all the file's (the runs then adjoin).
    constexpr size_t kBlock = 256;
    const size_t times = static_cast<size_t>(buffered_), run_values = times * 3;
    std::vector<float> runs(kBlock * run_values);
    const bool adjoining = buffered_ == times_;
    for (size_t p0 = 0; p0 < pixels_; p0 += kBlock) {
        const size_t n = std::min(kBlock, pixels_ - p0);
        for (size_t t = 0; t < times; ++t) {
            const float* plane = buffer_.data() + (t * pixels_ + p0) * 3;
            for (size_t q = 0; q < n; ++q) {
                float* to = runs.data() + q * run_values + t * 3;
                to[0] = plane[q * 3];
                to[1] = plane[q * 3 + 1];
                to[2] = plane[q * 3 + 2];
            }
        }
        auto write_at = [&](const float* from, size_t bytes, uint64_t at) {
            size_t done = 0;
            const char* bytes_from = reinterpret_cast<const char*>(from);
            while (done < bytes) {
                const ssize_t w = ::pwrite(fd_, bytes_from + done, bytes - done, static_cast<off_t>(at + done));
                if (w < 0 && errno == EINTR) continue;
                if (w <= 0) throw RuntimeFailure("--cube " + path_ + ": cannot write: " + std::strerror(errno));
                done += static_cast<size_t>(w);
            }
        };
        const uint64_t value_bytes = sizeof(float);
        if (adjoining) {
            write_at(runs.data(), n * run_values * value_bytes, data_offset_ + p0 * run_values * value_bytes);
            continue;
        }
        for (size_t q = 0; q < n; ++q)
            write_at(runs.data() + q * run_values, run_values * value_bytes,
                     data_offset_ + ((p0 + q) * static_cast<uint64_t>(times_) + first_buffered_) * 3 * value_bytes);
    }
    first_buffered_ += buffered_;
    buffered_ = 0;
}

void NpyTimeInnerWriter::finish() {
    if (fd_ < 0) return;
    if (written_ != times_) throw RuntimeFailure("--cube " + path_ + ": incomplete");
    const bool ok = ::close(fd_) == 0;
    fd_ = -1;
    if (!ok) {
        discard_file(temp_);
        throw RuntimeFailure("--cube " + path_ + ": cannot write: " + std::strerror(errno));
    }
    commit_file(temp_, path_);
}

NpyCube read_npy_cube(const std::string& path) {
    auto bad = [&](const std::string& why) { return InputError(path + ": " + why); };
    // A regular file only, and its size known before any allocation: the header's shape is
    // checked against it, so a small file claiming a huge shape allocates nothing.
    constexpr uint64_t kMaxCubeBytes = uint64_t(1) << 37;  // 128 GiB: as large as a shape may be
    const InputFileId file = check_input_file(path, kMaxCubeBytes, path, "NumPy .npy cube");
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw bad(std::string("cannot open: ") + std::strerror(errno));
    struct Closer { std::FILE* f; ~Closer() { std::fclose(f); } } closer{f};
    unsigned char pre[10];
    if (std::fread(pre, 1, 10, f) != 10 || std::memcmp(pre, "\x93NUMPY", 6) != 0 || pre[6] != 1)
        throw bad("not a NumPy .npy file (version 1)");
    size_t len = pre[8] | (static_cast<size_t>(pre[9]) << 8);
    std::string dict(len, '\0');
    if (std::fread(dict.data(), 1, len, f) != len) throw bad("truncated header");
    std::smatch m;
    static const std::regex shape_re(R"(\(\s*(\d+)\s*,\s*(\d+)\s*,\s*(\d+)\s*,\s*3\s*,?\s*\))");
    if (dict.find("'<f4'") == std::string::npos || dict.find("'fortran_order': False") == std::string::npos ||
        !std::regex_search(dict, m, shape_re))
        throw bad("expected a float32 C-order array of shape (planes, height, width, 3)");
    // Each dimension within bounds before any product is formed: no overflow.
    auto dim = [&](const std::string& text, long long max) {
        std::optional<long long> v = parse_whole<long long>(text);
        if (!v || *v < 1 || *v > max)
            throw bad("implausible shape: dimension " + (text.size() > 24 ? text.substr(0, 24) + "..." : text) +
                      " is not in 1.." + std::to_string(max));
        return *v;
    };
    NpyCube c;
    long long p = dim(m[1], 1000000), h = dim(m[2], 65536), w = dim(m[3], 65536);
    if (p * h * w > (1ll << 33)) throw bad("implausible shape: more than 2^33 pixels");
    const uint64_t need = 10 + len + static_cast<uint64_t>(p * h * w) * 3 * sizeof(float);
    if (file.size != need)
        throw bad("is " + std::to_string(file.size) + " bytes, but its shape (" + std::to_string(p) + ", " +
                  std::to_string(h) + ", " + std::to_string(w) + ", 3) needs " + std::to_string(need));
    c.planes = static_cast<int>(p);
    c.height = static_cast<int>(h);
    c.width = static_cast<int>(w);
    c.data.resize(static_cast<size_t>(p * h * w * 3));
    if (std::fread(c.data.data(), sizeof(float), c.data.size(), f) != c.data.size()) throw bad("truncated data");
    // Radiance is finite and never negative: anything else would be written on into frames.
    const size_t plane_values = static_cast<size_t>(h * w * 3);
    for (size_t i = 0; i < c.data.size(); ++i)
        if (!(c.data[i] >= 0 && c.data[i] <= std::numeric_limits<float>::max())) {
            const size_t px = (i % plane_values) / 3;
            throw bad("plane " + std::to_string(i / plane_values) + ", pixel (" + std::to_string(px % w) + ", " +
                      std::to_string(px / w) + "): value " + std::to_string(c.data[i]) +
                      " is not a finite radiance >= 0");
        }
    return c;
}

}  // namespace sl
