#pragma once
// For fuzz targets whose reader takes a path: the input bytes written to one scratch file per
// process (libFuzzer runs inputs one after another in a process).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace sl::fuzz {

inline std::string write_scratch(const uint8_t* data, size_t size, const char* ext) {
    static const std::string path = "/tmp/slowlight_fuzz_" + std::to_string(::getpid()) + ext;
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return path;
    std::fwrite(data, 1, size, f);
    std::fclose(f);
    return path;
}

}  // namespace sl::fuzz
