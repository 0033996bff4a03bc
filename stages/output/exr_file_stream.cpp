#include "stages/output/exr_file_stream.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <memory>
#include <stdexcept>

namespace sl {
namespace {

// One block per thread that writes EXRs, allocated once. 64 KiB: at 192 frames of 256x256
// (the demo's tail, whole-process system time, medians of 5) OpenEXR's own 3 KiB writes cost
// 0.70 s, 64 KiB blocks 0.48 s, 16 KiB 0.63 s, and a whole frame in one 1 MiB write 1.08 s:
// the kernel then spent its time copying into the page cache (larger writes, larger fresh
// folios there, which this virtual machine seems to hand out slowly).
constexpr uint64_t kBlock = 64u << 10;

thread_local std::unique_ptr<char[]> t_block;
thread_local bool t_block_taken = false;

[[noreturn]] void fail(const char* what, const std::string& path, int err) {
    throw std::runtime_error(std::string(what) + " " + path + ": " + std::strerror(err));
}

}  // namespace

ExrFileStream::ExrFileStream(const std::string& path)
    : Imf::OStream(path.c_str()), path_(path) {
    if (t_block_taken) {  // a second file open on this thread: a block of its own
        own_block_.reset(new char[kBlock]);
        buffer_ = own_block_.get();
    } else {
        if (!t_block) t_block.reset(new char[kBlock]);
        buffer_ = t_block.get();
        t_block_taken = true;
    }
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd_ < 0) {
        const int err = errno;
        if (!own_block_) t_block_taken = false;  // the destructor does not run
        fail("cannot create", path_, err);
    }
}

ExrFileStream::~ExrFileStream() {
    if (fd_ >= 0) ::close(fd_);
    if (!own_block_) t_block_taken = false;
}

void ExrFileStream::write(const char c[], int n) {
    if (n <= 0) return;
    const uint64_t bytes = static_cast<uint64_t>(n);
    if (buffered_ > 0 && (pos_ != buffer_at_ + buffered_ || buffered_ + bytes > kBlock)) flush();
    if (buffered_ == 0) buffer_at_ = pos_;
    if (bytes > kBlock) {  // larger than a block: straight to the file
        buffered_ = 0;
        uint64_t done = 0;
        while (done < bytes) {
            const ssize_t w = ::pwrite(fd_, c + done, bytes - done, static_cast<off_t>(pos_ + done));
            if (w < 0 && errno == EINTR) continue;
            if (w <= 0) fail("cannot write", path_, w < 0 ? errno : EIO);
            done += static_cast<uint64_t>(w);
        }
    } else {
        std::memcpy(buffer_ + buffered_, c, bytes);
        buffered_ += bytes;
    }
    pos_ += bytes;
}

void ExrFileStream::flush() {
    uint64_t done = 0;
    while (done < buffered_) {
        const ssize_t w = ::pwrite(fd_, buffer_ + done, buffered_ - done, static_cast<off_t>(buffer_at_ + done));
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) fail("cannot write", path_, w < 0 ? errno : EIO);
        done += static_cast<uint64_t>(w);
    }
    buffered_ = 0;
}

void ExrFileStream::close() {
    flush();
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail("cannot close", path_, errno);
}

}  // namespace sl
