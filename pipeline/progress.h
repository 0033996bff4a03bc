#pragma once
// A progress bar on stderr (passes done and time left), drawn only when stderr is a terminal.
#include <chrono>

namespace sl {

class ProgressBar {
public:
    ProgressBar(bool enabled, int sections, int passes_per_section);
    void update(int section, int pass);  // after `pass` passes of section `section` (0-based)
    void finish();

private:
    bool enabled_;
    int sections_, passes_;
    std::chrono::steady_clock::time_point start_, last_draw_;
    bool drawn_ = false;
};

}  // namespace sl
