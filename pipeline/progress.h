#pragma once
// A progress line on stderr (passes done per section and time left), drawn only when stderr is
// a terminal; messages printed through it never land on the end of the line being drawn.
#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace sl {

// Time left, from the passes' own durations (times in seconds from any origin, injected so the
// estimate can be checked without a clock). A pass gets cheaper as the radii shrink (the gather
// finds fewer photons; R_i^2 falls like i^-(1-alpha)), so the section's pass times are fitted
// with a + b i^-(1-alpha) and the fit is summed over the passes to come. Later sections cost
// more than earlier ones (they trace photons further): their passes are interpolated between
// this section's and a full-path pass (the exposure preview's), when known.
class TimeLeftEstimator {
public:
    TimeLeftEstimator(int sections, int passes_per_section, double alpha = 0.7);
    void set_passes(int passes_per_section) { passes_ = passes_per_section; }
    // The preview's average pass, over its first `passes` passes.
    void expect_full_pass(double seconds, int passes) { full_pass_ = seconds, full_passes_ = passes; }
    void skip_section(int section);  // finished already (resumed): nothing left to do there
    void section_started(int section, int passes_done, double t);
    void pass_done(int section, int passes_done, double t);
    // Nothing until two passes of this run are timed.
    std::optional<double> seconds_left() const;

private:
    int sections_, passes_;
    double exponent_;  // -(1 - alpha)
    double full_pass_ = 0;
    int full_passes_ = 1;
    int section_ = 0, passes_done_ = 0, first_pass_ = 0;
    double last_t_ = 0;
    std::vector<double> recent_;      // durations of this section's passes in this run
    std::vector<bool> skipped_;
};

class ProgressBar {
public:
    ProgressBar(bool enabled, int sections, int passes_per_section, double alpha = 0.7);
    void section_started(int section, int passes_done);
    void update(int section, int pass);  // after `pass` passes of section `section` (0-based)
    void set_passes(int passes);        // --time-limit fixed the number of passes
    void set_deadline(double seconds_from_now);
    void skip_section(int section);
    void expect_full_pass(double seconds, int passes) { estimate_.expect_full_pass(seconds, passes); }
    // Prints a whole line on stderr, clearing the progress line first (redrawn on the next update).
    void message(const std::string& line);
    void finish();

private:
    void draw(bool force);
    double now() const;
    bool enabled_;
    int sections_, passes_;
    std::vector<int> done_;  // passes done per section
    int section_ = 0;
    TimeLeftEstimator estimate_;
    std::optional<double> deadline_;
    std::chrono::steady_clock::time_point start_, last_draw_;
    bool drawn_ = false;
};

}  // namespace sl
