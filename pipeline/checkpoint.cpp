#include "pipeline/checkpoint.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <regex>

#include "foundation/errors.h"
#include "pipeline/distributed/section_state_on_ranks.h"

namespace sl {
namespace fs = std::filesystem;

std::string checkpoint_path(const std::string& dir, int section) {
    char name[40];
    std::snprintf(name, sizeof name, "section_%04d.ckpt", section);
    return (fs::path(dir) / name).string();
}

std::vector<std::string> checkpoint_files(const std::string& dir) {
    std::vector<std::string> out;
    std::error_code ec;
    if (dir.empty() || !fs::is_directory(dir, ec)) return out;
    static const std::regex name(R"(section_[0-9]{4,}\.ckpt)");
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (std::regex_match(e.path().filename().string(), name)) out.push_back(e.path().string());
    std::sort(out.begin(), out.end());
    return out;
}

void remove_stale_checkpoint_temps(const std::string& dir) {
    std::error_code ec;
    if (dir.empty() || !fs::is_directory(dir, ec)) return;
    static const std::regex name(R"(\.section_[0-9]{4,}\.ckpt\.tmp[0-9]+)");
    std::vector<fs::path> stale;
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (std::regex_match(e.path().filename().string(), name)) stale.push_back(e.path());
    for (const auto& p : stale) fs::remove(p, ec);
}

Checkpointer::Checkpointer(CheckpointSettings settings, SectionStateId id, RankExchange* ex)
    : settings_(std::move(settings)), id_(std::move(id)), ex_(ex), writer_(!ex || ex->rank() == 0),
      last_save_(Clock::now()), interval_(settings_.every) {
    if (!enabled() || !writer_) return;
    std::error_code ec;
    fs::create_directories(settings_.dir, ec);
    if (!fs::is_directory(settings_.dir))
        throw RuntimeFailure(settings_.flag + " " + settings_.dir + ": cannot create the directory" +
                             (ec ? ": " + ec.message() : std::string()));
}

SectionStateId Checkpointer::id_for(int section) const {
    SectionStateId id = id_;
    id.section = section;
    return id;
}

void Checkpointer::after_pass(const SectionBuffer& buffer) {
    if (!enabled() || settings_.every < 0) return;
    if (buffer.layout.index != last_section_) {  // a new section: its interval starts now
        std::lock_guard lock(mutex_);
        last_section_ = buffer.layout.index;
        last_passes_ = -1;
        last_save_ = Clock::now();
        if (settings_.every > 0) return;
    }
    bool due = std::chrono::duration<double>(Clock::now() - last_save_).count() >= interval_;
    if (ex_) due = ex_->broadcast(Channel::Passes, due);  // rank 0's clock, for every rank
    if (due) save(buffer, false);
}

std::string Checkpointer::save(const SectionBuffer& buffer, bool finished) {
    if (!enabled()) return "";
    const int section = buffer.layout.index;
    const std::string path = checkpoint_path(settings_.dir, section);
    {
        std::lock_guard lock(mutex_);
        if (section == last_section_ && buffer.passes_done == last_passes_ && !finished) return path;
    }
    auto t0 = Clock::now();
    uint64_t bytes = ex_ ? save_section_state_on_ranks(*ex_, path, buffer, id_for(section), finished)
                         : save_section_state(path, buffer, id_for(section), finished);
    double took = std::chrono::duration<double>(Clock::now() - t0).count();
    std::lock_guard lock(mutex_);
    last_section_ = section;
    last_passes_ = buffer.passes_done;
    last_save_ = Clock::now();
    // A checkpoint costs its write time; keep that under 2% of the render whatever its size.
    if (settings_.every > 0) interval_ = std::max(settings_.every, 50 * took);
    ++totals_.writes;
    totals_.last_bytes = bytes;
    totals_.seconds += took;
    totals_.longest = std::max(totals_.longest, took);
    return path;
}

void Checkpointer::remove(int section) {
    if (!enabled() || !writer_) return;
    std::error_code ec;
    fs::remove(checkpoint_path(settings_.dir, section), ec);
}

void Checkpointer::remove_all() {
    if (!writer_) return;
    for (const std::string& p : checkpoint_files(settings_.dir)) {
        std::error_code ec;
        fs::remove(p, ec);
    }
}

Checkpointer::Totals Checkpointer::totals() const {
    std::lock_guard lock(mutex_);
    return totals_;
}

}  // namespace sl
