#include "stages/output/exr_file_stream.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <memory>
#include <stdexcept>

namespace sl {
namespace {

// One block per file, from the heap (below main.cpp's mmap threshold: reused, not faulted in
// anew for every frame). 64 KiB: at 192 frames of 256x256 (the demo's tail, whole-process
// system time, medians of 5) OpenEXR's own 3 KiB writes cost
// 0.70 s, 64 KiB blocks 0.48 s, 16 KiB 0.63 s, and a whole frame in one 1 MiB write 1.08 s:
// the kernel then spent its time copying into the page cache (larger writes, larger fresh
// folios there, which this virtual machine seems to hand out slowly).
constexpr uint64_t kBlock = 64u << 10;

[[noreturn]] void fail(const char* what, const std::string& path, int err) {
    throw std::runtime_error(std::string(what) + " " + path + ": " + std::strerror(err));
}

// All of `bytes` at file offset `at`, however many calls the kernel needs.
void write_all(int fd, const char* data, uint64_t bytes, uint64_t at, const std::string& path) {
    uint64_t done = 0;
    while (done < bytes) {
        const ssize_t w = ::pwrite(fd, data + done, bytes - done, static_cast<off_t>(at + done));
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) fail("cannot write", path, w < 0 ? errno : EIO);
        done += static_cast<uint64_t>(w);
    }
}

}  // namespace

ExrFileStream::ExrFileStream(const std::string& path)
    : Imf::OStream(path.c_str()), path_(path), buffer_(new char[kBlock]) {
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd_ < 0) fail("cannot create", path_, errno);
}

ExrFileStream::~ExrFileStream() {
    if (fd_ >= 0) ::close(fd_);
}

void ExrFileStream::write(const char c[], int n) {
    if (n <= 0) return;
    const uint64_t bytes = static_cast<uint64_t>(n);
    if (buffered_ > 0 && (pos_ != buffer_at_ + buffered_ || buffered_ + bytes > kBlock)) flush();
    if (buffered_ == 0) buffer_at_ = pos_;
    if (bytes > kBlock) {  // larger than a block: straight to the file
        buffered_ = 0;
        write_all(fd_, c, bytes, pos_, path_);
    } else {
        std::memcpy(buffer_.get() + buffered_, c, bytes);
        buffered_ += bytes;
    }
    pos_ += bytes;
}

void ExrFileStream::flush() {
    write_all(fd_, buffer_.get(), buffered_, buffer_at_, path_);
    buffered_ = 0;
}

void ExrFileStream::close() {
    flush();
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail("cannot close", path_, errno);
}

}  // namespace sl
