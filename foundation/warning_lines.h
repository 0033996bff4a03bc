#pragma once
// Where `warning:` lines go: stderr, as the program prints them, unless the thread has a sink
// (the Python module takes the lines of the scene it loads to Python's warnings module).
#include <cstdio>
#include <functional>
#include <string>

namespace sl {

using WarningSink = std::function<void(const std::string& line)>;

// This thread's sink; empty: stderr.
inline WarningSink& thread_warning_sink() {
    thread_local WarningSink sink;
    return sink;
}

// One whole line, "warning: ..." included.
inline void emit_warning(const std::string& line) {
    if (const WarningSink& sink = thread_warning_sink()) sink(line);
    else std::fprintf(stderr, "%s\n", line.c_str());
}

// Sends this thread's warnings to `sink` while it lives.
class ScopedWarningSink {
public:
    explicit ScopedWarningSink(WarningSink sink) : previous_(std::move(thread_warning_sink())) {
        thread_warning_sink() = std::move(sink);
    }
    ~ScopedWarningSink() { thread_warning_sink() = std::move(previous_); }
    ScopedWarningSink(const ScopedWarningSink&) = delete;
    ScopedWarningSink& operator=(const ScopedWarningSink&) = delete;

private:
    WarningSink previous_;
};

}  // namespace sl
