#pragma once
// Checkpoints of the section in progress (docs/checkpoints.md): where they live, when they are
// written, which ones a --resume finds. The file format is stages/render/section_state_io.h.
//
// DIR/section_0000.ckpt holds section 1's state. It is written every `every` seconds (after the
// pass that crosses the interval) and at an interrupt, and removed once the section's frames
// are in --exr-dir. Without --exr-dir, a finished section's final state is kept instead (so a
// --resume can write its frames again) until the whole render has succeeded.
#include <chrono>
#include <mutex>
#include <string>
#include <vector>

#include "stages/render/section_state_io.h"

namespace sl {

inline constexpr double kDefaultCheckpointEvery = 300;  // seconds

struct CheckpointSettings {
    std::string dir;       // empty: no checkpoints
    double every = kDefaultCheckpointEvery;  // seconds; 0: after every pass; < 0: only at an interrupt
    bool keep_finished = false;              // no --exr-dir and more than one section
    std::string flag = "--checkpoint";       // the option that named `dir`, for messages
};

std::string checkpoint_path(const std::string& dir, int section);

// The checkpoint files in `dir` (section_NNNN.ckpt), sorted; none when `dir` does not exist.
std::vector<std::string> checkpoint_files(const std::string& dir);

// Removes temporary files a killed checkpoint write left behind (.section_NNNN.ckpt.tmpPID).
void remove_stale_checkpoint_temps(const std::string& dir);

class Checkpointer {
public:
    // With several ranks (`ex`), every rank holds one and makes the same calls; only rank 0
    // makes the directory and writes the files, from every rank's pixels, and its clock decides
    // when a checkpoint is due.
    Checkpointer(CheckpointSettings settings, SectionStateId id, RankExchange* ex = nullptr);
    bool enabled() const { return !settings_.dir.empty(); }
    const CheckpointSettings& settings() const { return settings_; }
    SectionStateId id_for(int section) const;

    // After each pass: saves when the interval has passed since the section's last save.
    void after_pass(const SectionBuffer& buffer);
    // Saves now unless this state is already on disk. Returns the path ("" when disabled).
    std::string save(const SectionBuffer& buffer, bool finished);
    void remove(int section);
    void remove_all();

    struct Totals {
        int writes = 0;
        uint64_t last_bytes = 0;
        double seconds = 0, longest = 0;
    };
    Totals totals() const;

private:
    using Clock = std::chrono::steady_clock;
    CheckpointSettings settings_;
    SectionStateId id_;
    RankExchange* ex_ = nullptr;
    bool writer_ = true;  // rank 0, or one process
    mutable std::mutex mutex_;
    Clock::time_point last_save_;
    int last_section_ = -1, last_passes_ = -1;
    double interval_;  // `every`, raised so that writing takes at most 2% of the time
    Totals totals_;
};

}  // namespace sl
