#pragma once
// --time-limit: render passes until the wall-time budget is spent, every section the same
// number of passes (--passes stays the upper bound).
//
// The first section rendered decides the number n: it stops before a pass when finishing that
// pass and then n of them in each later section would overrun the budget (a later section's
// pass is estimated from the exposure preview, which traces full paths like the most costly
// section, or else from this section's own passes). Later sections render n passes; only if
// they run 25% past the budget are they cut short (the stats then show fewer passes for them).
#include <chrono>
#include <optional>

namespace sl {

class TimeBudget {
public:
    using Clock = std::chrono::steady_clock;
    TimeBudget() = default;  // unlimited
    TimeBudget(double seconds, Clock::time_point start, int sections_to_render);

    bool limited() const { return limit_ > 0; }
    // The number of passes every section gets, once decided (or nothing yet).
    std::optional<int> passes() const { return fixed_ > 0 ? std::optional<int>(fixed_) : std::nullopt; }
    double limit_seconds() const { return limit_; }

    // A pass of a later section is expected to take about this long (the preview's average).
    void expect_later_pass(double seconds) { later_pass_ = seconds; }
    // The preview for the exposure gets a sixteenth of the budget.
    bool preview_over(int passes_done) const;

    void section_started(int passes_done);
    // Asked before each pass: true to stop the section here.
    bool stop_before_pass(int passes_done);
    void pass_done(int passes_done);
    // The section ended with this many passes (by the budget, by --passes or an interrupt).
    void section_finished(int passes_done, bool interrupted);

private:
    double elapsed(Clock::time_point t) const { return std::chrono::duration<double>(t - start_).count(); }
    double limit_ = 0;
    Clock::time_point start_{}, section_start_{}, last_pass_end_{};
    int sections_left_ = 0;     // including the one rendering
    int first_pass_ = 0;        // passes done when this section started (resumed sections)
    double last_pass_ = 0;      // seconds the latest pass took
    double later_pass_ = 0;
    int fixed_ = 0;
};

}  // namespace sl
