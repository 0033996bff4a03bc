#pragma once
// Shared by the interrupt, checkpoint and time-limit tests: small renders of the real program,
// and ways to read back what they wrote.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "process.h"
#include "stages/output/exr_io.h"

namespace sl::test {

inline nlohmann::json read_json(const std::string& path) {
    std::ifstream f(path);
    return nlohmann::json::parse(f, nullptr, /*allow_exceptions=*/false);
}

inline std::string frame_name(int k) {
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%04d.exr", k);
    return name;
}

// Waits until `path` exists, at most `seconds`.
inline bool wait_for(const std::string& path, double seconds = 120) {
    for (int i = 0; i < seconds * 500; ++i) {
        if (std::filesystem::exists(path)) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return false;
}

// Every EXR of `a` (frames 0..frames-1 and steady.exr) equals the one of `b`, value for value.
inline void expect_same_exrs(const std::string& a, const std::string& b, int frames) {
    for (int k = 0; k < frames; ++k)
        EXPECT_EQ(read_exr(a + frame_name(k)).rgb, read_exr(b + frame_name(k)).rgb) << a << frame_name(k);
    EXPECT_EQ(read_exr(a + "/steady.exr").rgb, read_exr(b + "/steady.exr").rgb) << a;
}

// `slowlight render` with these settings, its frames in DIR/SUB and its video in DIR/SUB.mkv.
inline std::vector<std::string> render_into(const std::string& dir, const std::string& sub,
                                            const std::vector<std::string>& settings) {
    std::vector<std::string> a{"render"};
    a.insert(a.end(), settings.begin(), settings.end());
    a.insert(a.end(), {"--exr-dir", dir + "/" + sub, "-o", dir + "/" + sub + ".mkv", "--no-progress"});
    return a;
}

inline std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
    args.insert(args.end(), more.begin(), more.end());
    return args;
}

}  // namespace sl::test
