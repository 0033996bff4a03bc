#include "pipeline/time_budget.h"

#include <algorithm>

namespace sl {

TimeBudget::TimeBudget(double seconds, Clock::time_point start, int sections_to_render)
    : limit_(seconds), start_(start), sections_left_(std::max(1, sections_to_render)) {}

bool TimeBudget::preview_over(int passes_done) const {
    return limited() && passes_done >= 1 && elapsed(Clock::now()) > limit_ / 16;
}

void TimeBudget::section_started(int passes_done) {
    section_start_ = last_pass_end_ = Clock::now();
    first_pass_ = passes_done;
    last_pass_ = 0;
}

void TimeBudget::pass_done(int) {
    auto now = Clock::now();
    last_pass_ = std::chrono::duration<double>(now - last_pass_end_).count();
    last_pass_end_ = now;
}

bool TimeBudget::stop_before_pass(int passes_done) {
    if (!limited()) return false;
    const auto now = Clock::now();
    if (fixed_ > 0) return passes_done >= fixed_ || (passes_done >= 1 && elapsed(now) + last_pass_ > 1.25 * limit_);
    if (passes_done - first_pass_ < 1) return false;  // every section gets at least one pass here
    // Would one more pass here, and as many in every later section, still fit?
    const double own = std::chrono::duration<double>(now - section_start_).count() / (passes_done - first_pass_);
    const double later = later_pass_ > 0 ? later_pass_ : own;
    const double projected = elapsed(now) + last_pass_ + (sections_left_ - 1) * (passes_done + 1) * later;
    return projected > limit_;
}

void TimeBudget::section_finished(int passes_done, bool interrupted) {
    if (!limited() || interrupted) return;
    if (fixed_ == 0) fixed_ = std::max(1, passes_done);
    sections_left_ = std::max(1, sections_left_ - 1);
}

}  // namespace sl
