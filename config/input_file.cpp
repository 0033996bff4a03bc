#include "config/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "foundation/errors.h"

namespace sl {
namespace {

std::string mib(uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; }

[[noreturn]] void refuse(const struct stat& st, const std::string& label, const std::string& kind) {
    if (S_ISDIR(st.st_mode)) throw InputError(label + ": is a directory, not a " + kind);
    throw InputError(label + ": is " + file_kind_name(st.st_mode) + ", not a " + kind +
                     " (only regular files are read)");
}

InputFileId checked(const struct stat& st, uint64_t max_bytes, const std::string& label, const std::string& kind) {
    if (!S_ISREG(st.st_mode)) refuse(st, label, kind);
    const uint64_t size = static_cast<uint64_t>(st.st_size);
    if (size > max_bytes)
        throw InputError(label + ": is " + mib(size) + ", more than the " + mib(max_bytes) + " a " + kind +
                         " may have");
    return {size, static_cast<uint64_t>(st.st_dev), static_cast<uint64_t>(st.st_ino)};
}

struct Fd {
    int fd = -1;
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
};

}  // namespace

std::string file_kind_name(unsigned mode) {
    if (S_ISREG(mode)) return "a regular file";
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

InputFileId check_input_file(const std::string& path, uint64_t max_bytes, const std::string& label,
                             const std::string& kind) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw InputError(label + ": cannot open the " + kind + ": " + std::strerror(errno));
    return checked(st, max_bytes, label, kind);
}

void read_input_chunks(const std::string& path, uint64_t max_bytes, const std::string& label,
                       const std::string& kind, const std::function<void(const char*, size_t)>& chunk) {
    check_input_file(path, max_bytes, label, kind);
    Fd f;
    f.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (f.fd < 0) throw InputError(label + ": cannot open the " + kind + ": " + std::strerror(errno));
    struct stat st {};
    if (::fstat(f.fd, &st) != 0) throw InputError(label + ": cannot read the " + kind + ": " + std::strerror(errno));
    checked(st, max_bytes, label, kind);  // the file opened is the file checked
    ::fcntl(f.fd, F_SETFL, ::fcntl(f.fd, F_GETFL) & ~O_NONBLOCK);
    char buf[1 << 16];
    uint64_t total = 0;
    for (;;) {
        ssize_t n = ::read(f.fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw InputError(label + ": cannot read the " + kind + ": " + std::strerror(errno));
        if (n == 0) break;
        total += static_cast<uint64_t>(n);
        if (total > max_bytes)  // grew while being read
            throw InputError(label + ": is more than the " + mib(max_bytes) + " a " + kind + " may have");
        chunk(buf, static_cast<size_t>(n));
    }
}

std::string read_input_file(const std::string& path, uint64_t max_bytes, const std::string& label,
                            const std::string& kind) {
    std::string text;
    read_input_chunks(path, max_bytes, label, kind, [&](const char* p, size_t n) { text.append(p, n); });
    return text;
}

}  // namespace sl
