// The progress line's time left: right within 20% after the first few passes, for a render
// whose later sections cost more per pass than the first (they trace photons further) and
// whose passes get cheaper as the radii shrink — the shape measured on the demo with 4
// sections (0.19, 0.26, 0.29, 0.38 s per pass; a full-path preview pass 0.41 s).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "pipeline/progress.h"

namespace sl {
namespace {

struct Render {
    std::vector<double> per_pass;  // per section: the average cost of its passes
    int passes = 64;
    double full_pass = 0;          // the preview's pass, 0: unknown (one section)
    // Cheaper as the radii shrink (the gather finds fewer photons), averaging per_pass.
    // (On the demo the first passes of a section cost about 30% more than its last ones.)
    static double shape(int pass) { return 0.7 + 0.5 * std::pow(pass + 1.0, -0.3); }
    // And +-15% from pass to pass (a machine shared with other work), the same every run.
    static double jitter(int section, int pass) {
        uint32_t h = static_cast<uint32_t>(section * 7919 + pass) * 2654435761u;
        return 1.0 + 0.15 * ((h >> 8) / double(1u << 24) * 2 - 1);
    }
    double cost(int section, int pass) const {
        double mean = 0;
        for (int p = 0; p < passes; ++p) mean += shape(p) / passes;
        return per_pass[section] * shape(pass) / mean * jitter(section, pass);
    }
};

// Largest relative error of the estimate over every pass after the `warmup`-th of each section.
double worst_error(const Render& r, int warmup) {
    const int K = static_cast<int>(r.per_pass.size());
    std::vector<double> end_of;  // time at which each (section, pass) ends
    double t = 0;
    for (int s = 0; s < K; ++s)
        for (int p = 0; p < r.passes; ++p) end_of.push_back(t += r.cost(s, p));
    const double total = t;
    TimeLeftEstimator e(K, r.passes);
    if (r.full_pass > 0) e.expect_full_pass(r.full_pass, r.passes / 8);
    double worst = 0, now = 0;
    for (int s = 0; s < K; ++s) {
        e.section_started(s, 0, now);
        for (int p = 0; p < r.passes; ++p) {
            now = end_of[static_cast<size_t>(s * r.passes + p)];
            e.pass_done(s, p + 1, now);
            const double truth = total - now;
            if (p + 1 < warmup || truth < 1e-9) continue;
            std::optional<double> left = e.seconds_left();
            EXPECT_TRUE(left.has_value());
            double err = std::abs(left.value_or(0) - truth) / truth;
            if (err > worst && getenv("TL_DEBUG")) std::printf("  s%d p%d err %.3f\n", s, p + 1, err);
            worst = std::max(worst, err);
        }
    }
    return worst;
}

TEST(TimeLeft, OneSectionWithinTwentyPercentAfterAFewPasses) {
    const double worst = worst_error(Render{{0.12}, 64, 0}, 6);
    std::printf("worst error after the 6th pass: %.1f%%\n", 100 * worst);
    EXPECT_LT(worst, 0.20);
}

TEST(TimeLeft, FourSectionsOfRisingCostWithinTwentyPercent) {
    const double worst = worst_error(Render{{0.19, 0.26, 0.29, 0.38}, 64, 0.41}, 6);
    std::printf("worst error after the 6th pass of each section: %.1f%%\n", 100 * worst);
    EXPECT_LT(worst, 0.20);
}

TEST(TimeLeft, NothingBeforeTwoPassesAreTimed) {
    TimeLeftEstimator e(1, 10);
    e.section_started(0, 0, 5.0);
    EXPECT_FALSE(e.seconds_left().has_value());
    e.pass_done(0, 1, 6.0);
    EXPECT_FALSE(e.seconds_left().has_value());
    e.pass_done(0, 2, 7.0);
    ASSERT_TRUE(e.seconds_left().has_value());
    EXPECT_NEAR(*e.seconds_left(), 8.0, 1e-9);  // 8 passes of 1 s: the time before the first pass is not one
}

TEST(TimeLeft, ResumedSectionsCountNothing) {
    TimeLeftEstimator e(3, 10);
    e.skip_section(2);  // its frames are on disk already
    e.section_started(0, 0, 0.0);
    for (int p = 1; p <= 4; ++p) e.pass_done(0, p, p * 1.0);
    ASSERT_TRUE(e.seconds_left().has_value());
    EXPECT_NEAR(*e.seconds_left(), 6.0 + 10.0, 1e-9);  // the rest of section 1, all of section 2
}

}  // namespace
}  // namespace sl
