#include "stages/output/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <system_error>

#include "core/errors.h"

namespace sl {

namespace fs = std::filesystem;

std::string temp_sibling(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    const fs::path p(path);
    const std::string name = "." + p.filename().string() + ".tmp" + std::to_string(::getpid()) +
                             "_" + std::to_string(counter++);
    return (p.parent_path() / name).string();
}

void commit_file(const std::string& temp, const std::string& path) {
    std::error_code ec;
    fs::rename(temp, path, ec);
    if (ec) {
        discard_file(temp);
        throw RuntimeFailure("cannot write '" + path + "': " + ec.message());
    }
}

void discard_file(const std::string& temp) noexcept {
    std::error_code ec;
    fs::remove(temp, ec);
}

std::string one_line(std::string text) {
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

}  // namespace sl
