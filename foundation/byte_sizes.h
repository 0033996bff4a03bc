#pragma once
// Byte counts as people read them ("1.25 GiB", "3.0 MiB"), for every message and report that
// states what something costs.
#include <cstdint>
#include <cstdio>
#include <string>

namespace sl {

inline std::string format_bytes(uint64_t bytes) {
    char buf[64];
    double b = static_cast<double>(bytes);
    if (b >= 1024.0 * 1024 * 1024) std::snprintf(buf, sizeof buf, "%.2f GiB", b / (1024.0 * 1024 * 1024));
    else if (b >= 1024.0 * 1024) std::snprintf(buf, sizeof buf, "%.1f MiB", b / (1024.0 * 1024));
    else if (b >= 1024.0) std::snprintf(buf, sizeof buf, "%.1f KiB", b / 1024.0);
    else std::snprintf(buf, sizeof buf, "%llu B", static_cast<unsigned long long>(bytes));
    return buf;
}

}  // namespace sl
