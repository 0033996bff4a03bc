#include "stages/output/atomic_file.h"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "foundation/errors.h"
#include "stages/output/live_temporaries.h"

namespace sl {

namespace fs = std::filesystem;

namespace {

// The id this process recorded a temporary under: N of `.slowlight-tmp-<pid>-<N>-<name>`
// (-1: not one of ours). Reads the text in place: it runs in noexcept code.
int64_t temp_id(const std::string& temp) noexcept {
    const size_t slash = temp.rfind('/');
    const char* name = temp.c_str() + (slash == std::string::npos ? 0 : slash + 1);
    if (std::strncmp(name, kTempPrefix, std::strlen(kTempPrefix)) != 0) return -1;
    const char* pid = name + std::strlen(kTempPrefix);
    char* after = nullptr;
    const unsigned long long writer = std::strtoull(pid, &after, 10);
    if (after == pid || *after != '-' || writer != static_cast<unsigned long long>(::getpid())) return -1;
    const char* n = after + 1;
    const unsigned long long id = std::strtoull(n, &after, 10);
    if (after == n || *after != '-') return -1;
    return static_cast<int64_t>(id);
}

void forget(const std::string& temp) noexcept {
    const int64_t id = temp_id(temp);
    if (id >= 0) forget_temporary(static_cast<uint64_t>(id));
}

bool is_temp_name(const fs::path& p) { return p.filename().string().rfind(kTempPrefix, 0) == 0; }

// A link that leads through a process's descriptor table names an open file, not a place.
bool through_descriptor(const fs::path& p) {
    const std::string s = p.lexically_normal().string();
    return s.rfind("/proc/", 0) == 0 || s.rfind("/dev/fd/", 0) == 0;
}

}  // namespace

OutputPlace place_output(const std::string& path) {
    OutputPlace place;
    place.path = path;
    if (path.empty()) return place;
    fs::path p(path);
    std::error_code ec;
    for (int hop = 0; hop < 40; ++hop) {
        auto st = fs::symlink_status(p, ec);
        if (ec || st.type() == fs::file_type::not_found) break;  // a new file
        if (st.type() == fs::file_type::symlink) {
            if (through_descriptor(p)) {
                place.in_place = true;
                place.path = path;
                return place;
            }
            fs::path target = fs::read_symlink(p, ec);
            if (ec) break;
            p = target.is_absolute() ? target : p.parent_path() / target;
            continue;
        }
        if (st.type() == fs::file_type::directory) place.directory = true;
        else if (st.type() != fs::file_type::regular) {
            place.in_place = true;
            place.path = path;  // write through the name the user gave
            return place;
        }
        break;
    }
    place.path = p.string();
    return place;
}

std::string temp_sibling(const std::string& path) {
    static std::atomic<uint64_t> counter{0};
    const OutputPlace place = place_output(path);
    if (place.in_place) return place.path;
    const fs::path p(place.path);
    const uint64_t id = counter++;
    const std::string name = std::string(kTempPrefix) + std::to_string(::getpid()) + "-" + std::to_string(id) + "-" +
                             p.filename().string();
    std::string temp = (p.parent_path() / name).string();
    remember_temporary(id, temp);
    return temp;
}

void commit_file(const std::string& temp, const std::string& path) {
    if (!is_temp_name(temp)) return;  // written in place
    std::error_code ec;
    fs::rename(temp, place_output(path).path, ec);
    if (ec) {
        discard_file(temp);
        throw RuntimeFailure("cannot write '" + path + "': " + ec.message());
    }
    forget(temp);
}

void discard_file(const std::string& temp) noexcept {
    if (!is_temp_name(temp)) return;  // a device or FIFO written in place is not ours to remove
    std::error_code ec;
    fs::remove(temp, ec);
    forget(temp);
}

int remove_stale_temporaries(const std::string& dir) noexcept {
    int removed = 0;
    std::error_code ec;
    fs::directory_iterator it(dir.empty() ? fs::path(".") : fs::path(dir), ec), end;
    for (; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.rfind(kTempPrefix, 0) != 0) continue;
        const char* digits = name.c_str() + std::strlen(kTempPrefix);
        char* after = nullptr;
        long pid = std::strtol(digits, &after, 10);
        if (after == digits || *after != '-' || pid <= 0) continue;
        if (pid == ::getpid()) continue;
        if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // alive (or not ours to judge)
        std::error_code rm;
        if (fs::remove(it->path(), rm)) ++removed;
    }
    return removed;
}

std::string one_line(std::string text) {
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

}  // namespace sl
