#include "pipeline/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace sl {

TimeLeftEstimator::TimeLeftEstimator(int sections, int passes, double alpha)
    : sections_(sections), passes_(passes), exponent_(-(1.0 - alpha)),
      skipped_(static_cast<size_t>(std::max(1, sections)), false) {}

void TimeLeftEstimator::skip_section(int s) {
    if (s >= 0 && s < sections_) skipped_[s] = true;
}

void TimeLeftEstimator::section_started(int s, int passes_done, double t) {
    section_ = s;
    passes_done_ = first_pass_ = passes_done;
    last_t_ = t;
    recent_.clear();
}

void TimeLeftEstimator::pass_done(int s, int passes_done, double t) {
    if (s != section_) section_started(s, passes_done - 1, last_t_);
    recent_.push_back(t - last_t_);
    last_t_ = t;
    passes_done_ = passes_done;
}

std::optional<double> TimeLeftEstimator::seconds_left() const {
    if (recent_.size() < 2) return std::nullopt;
    // Least squares t_i = a + b g(i), g(i) = i^-(1-alpha), over this section's passes so far.
    auto g = [&](int i) { return std::pow(static_cast<double>(std::max(i, 1)), exponent_); };
    const size_t n = recent_.size();
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t k = 0; k < n; ++k) {
        double x = g(first_pass_ + static_cast<int>(k) + 1), y = recent_[k];
        sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    double a = sy / n, b = 0;
    const double det = n * sxx - sx * sx;
    if (n >= 3 && det > 1e-12) {
        b = (n * sxy - sx * sy) / det;
        a = (sy - b * sx) / n;
        if (b < 0) a = sy / n, b = 0;            // noise: no decline seen
        if (a < 0) a = 0, b = sxy / sxx;         // all of it declines
    }
    auto cost = [&](int i) { return a + b * g(i); };
    auto sum = [&](int from, int to) {  // passes from..to, 1-based, inclusive
        double total = 0;
        for (int i = from; i <= to; ++i) total += cost(i);
        return total;
    };
    // On a busy machine a fit to a few noisy passes can promise too steep a decline: take the
    // mean of the fit's forecast and the latest quarter of the passes' plain average.
    const size_t window = std::max<size_t>(2, n / 4);
    const double recent = std::accumulate(recent_.end() - static_cast<std::ptrdiff_t>(window), recent_.end(), 0.0) /
                          static_cast<double>(window);
    const int to_go = std::max(0, passes_ - passes_done_);
    double left = 0.5 * (sum(passes_done_ + 1, passes_) + to_go * recent);
    const double section_now = 0.5 * (sum(1, passes_) + passes_ * recent);  // a whole section at this cost
    // The preview's passes are early (costlier) ones but trace no frame's buckets; measured on
    // the demo, its mean pass is close to the last section's (0.41 s against 0.38 s).
    const double section_full = full_pass_ > 0 ? full_pass_ * passes_ : section_now;
    const int last = sections_ - 1;
    for (int k = section_ + 1; k < sections_; ++k) {
        if (skipped_[k]) continue;
        const double f = last > section_ ? static_cast<double>(k - section_) / (last - section_) : 1.0;
        left += section_now + (section_full - section_now) * f;
    }
    return left;
}

ProgressBar::ProgressBar(bool enabled, int sections, int passes, double alpha)
    : enabled_(enabled && isatty(STDERR_FILENO)), sections_(sections), passes_(passes),
      done_(static_cast<size_t>(std::max(1, sections)), 0), estimate_(sections, passes, alpha),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

double ProgressBar::now() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ProgressBar::section_started(int section, int passes_done) {
    section_ = section;
    done_[section] = passes_done;
    estimate_.section_started(section, passes_done, now());
}

void ProgressBar::update(int section, int pass) {
    section_ = section;
    done_[section] = pass;
    estimate_.pass_done(section, pass, now());
    draw(false);
}

void ProgressBar::set_passes(int passes) {
    passes_ = passes;
    estimate_.set_passes(passes);
}

void ProgressBar::set_deadline(double seconds_from_now) { deadline_ = now() + seconds_from_now; }

void ProgressBar::skip_section(int section) {
    if (section >= 0 && section < sections_) done_[section] = passes_;
    estimate_.skip_section(section);
}

void ProgressBar::draw(bool force) {
    if (!enabled_) return;
    auto t = std::chrono::steady_clock::now();
    if (!force && t - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = t;
    int done = 0;
    for (int d : done_) done += std::min(d, passes_);
    const int total = sections_ * passes_, width = 24;
    int filled = total > 0 ? width * done / total : width;
    std::string bar(static_cast<size_t>(std::clamp(filled, 0, width)), '#');
    bar.resize(width, '.');
    std::string per;  // passes done per section: "64 64 12 0"
    if (sections_ > 1) {
        per = " [";
        for (int s = 0; s < sections_ && s < 12; ++s) per += (s ? " " : "") + std::to_string(done_[s]);
        per += sections_ > 12 ? " ...]" : "]";
    }
    std::optional<double> left = estimate_.seconds_left();
    if (deadline_) left = std::max(0.0, std::min(left.value_or(*deadline_ - now()), *deadline_ - now()));
    char eta[32] = "--:-- left";
    if (left) {
        long s = static_cast<long>(*left + 0.5);
        if (s >= 3600)
            std::snprintf(eta, sizeof eta, "%ld:%02ld:%02ld left", s / 3600, (s / 60) % 60, s % 60);
        else
            std::snprintf(eta, sizeof eta, "%ld:%02ld left", s / 60, s % 60);
    }
    std::fprintf(stderr, "\r\033[K[%s] section %d/%d, pass %d/%d%s, %s", bar.c_str(), section_ + 1, sections_,
                 done_[section_], passes_, per.c_str(), eta);
    std::fflush(stderr);
    drawn_ = true;
}

void ProgressBar::message(const std::string& line) {
    if (drawn_) std::fprintf(stderr, "\r\033[K");
    std::fprintf(stderr, "%s\n", line.c_str());
    std::fflush(stderr);
    if (drawn_) draw(true);
}

void ProgressBar::finish() {
    if (drawn_) std::fprintf(stderr, "\n");
    drawn_ = false;
}

}  // namespace sl
