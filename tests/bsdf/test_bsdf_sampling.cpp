// Each sampler's density against its pdf(): a chi-square goodness-of-fit over the sphere for
// every kind, roughness and incident angle (incl. 89 degrees and from below), as Mitsuba 3
// tests its BSDFs; pdf() integrates to at most 1 and to the share of draws the sampler keeps;
// and the mean sample weight equals the albedo integrated from eval (a second path to it).
#include <gtest/gtest.h>

#include <random>

#include "tests/bsdf/bsdf_cases.h"
#include "tests/bsdf/chi_square.h"
#include "tests/bsdf/sphere_quadrature.h"

namespace sl::test {
namespace {

constexpr int kSamples = 500000;
constexpr double kSignificance = 0.01;

struct Drawn {
    std::vector<double> histogram;
    double kept = 0;
    Vec3 mean_weight;
};

Drawn draw(const bsdf::Bsdf& b, Vec3 wo, const SphereGrid& grid, uint64_t seed, int samples = kSamples) {
    Drawn d;
    d.histogram.assign(static_cast<size_t>(grid.cells()), 0);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    double w[3] = {0, 0, 0};
    for (int i = 0; i < samples; ++i) {
        const float uc = u(rng), u1 = u(rng), u2 = u(rng);
        const bsdf::Sample s = bsdf::sample(b, wo, uc, u1, u2);
        if (!s.valid) continue;
        d.histogram[static_cast<size_t>(grid.cell_of(s.wi))] += 1;
        d.kept += 1;
        for (int c = 0; c < 3; ++c) w[c] += s.weight[c];
    }
    d.mean_weight = Vec3(static_cast<float>(w[0] / samples), static_cast<float>(w[1] / samples),
                         static_cast<float>(w[2] / samples));
    return d;
}

TEST(BsdfSampling, ChiSquareOfEverySamplerAgainstItsPdf) {
    const SphereGrid grid;
    const std::vector<BsdfCase> cases = bsdf_cases();
    size_t tests = 0;
    for (const BsdfCase& c : cases) tests += incident_directions(c.b).size();
    // Sidak: the chance that any of the tests fails by chance stays kSignificance.
    const double alpha = 1 - std::pow(1 - kSignificance, 1.0 / static_cast<double>(tests));
    uint64_t seed = 1;
    for (const BsdfCase& c : cases) {
        for (Vec3 wo : incident_directions(c.b)) {
            SCOPED_TRACE(c.name + " wo.z=" + std::to_string(wo.z));
            const Drawn d = draw(c.b, wo, grid, seed++);  // (a complex-index conductor samples as a Schlick one)
            const std::vector<double> p = integrate_cells(grid, [&](Vec3 wi) { return bsdf::pdf(c.b, wo, wi); });
            std::vector<double> expected(p.size());
            double total = 0;
            for (size_t i = 0; i < p.size(); ++i) {
                expected[i] = p[i] * kSamples;
                total += p[i];
            }
            EXPECT_LE(total, 1.0 + 2e-3) << "pdf integrates to more than 1";
            // The pdf's mass is the share of draws kept (the rest leave the lobe: GGX's loss);
            // 5e-3: the quadrature's error at 89 degrees, where rough refraction peaks at the horizon.
            EXPECT_NEAR(d.kept / kSamples, total, 4 * std::sqrt(std::max(0.0, total * (1 - total)) / kSamples) + 5e-3);
            const ChiSquareResult r = chi_square(d.histogram, expected);
            EXPECT_TRUE(r.failure.empty()) << r.failure;
            EXPECT_GT(r.p_value, alpha) << "chi-square " << r.statistic << " with " << r.dof << " dof";
        }
    }
}

TEST(BsdfSampling, MeanWeightIsTheAlbedoIntegratedFromEval) {
    const SphereGrid grid;
    uint64_t seed = 1000;
    for (const BsdfCase& c : bsdf_cases()) {
        for (Vec3 wo : incident_directions(c.b)) {
            SCOPED_TRACE(c.name + " wo.z=" + std::to_string(wo.z));
            const Drawn d = draw(c.b, wo, grid, seed++, 400000);
            const std::array<double, 3> albedo =
                integrate_sphere(grid, [&](Vec3 wi) { return bsdf::eval(c.b, wo, wi) * std::abs(wi.z); });
            // Monte Carlo error: the weights are bounded by a few here; 4e5 draws.
            for (int ch = 0; ch < 3; ++ch)
                EXPECT_NEAR(d.mean_weight[ch], albedo[ch], 0.01 * std::max(1.0, albedo[ch])) << "channel " << ch;
        }
    }
}

TEST(BsdfSampling, SampleWeightIsEvalCosOverPdf) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (const BsdfCase& c : bsdf_cases()) {
        for (Vec3 wo : incident_directions(c.b)) {
            for (int i = 0; i < 2000; ++i) {
                const bsdf::Sample s = bsdf::sample(c.b, wo, u(rng), u(rng), u(rng));
                if (!s.valid) continue;
                ASSERT_TRUE(is_finite(s.weight)) << c.name;
                const Vec3 f = bsdf::eval(c.b, wo, s.wi);
                const float p = bsdf::pdf(c.b, wo, s.wi);
                ASSERT_GT(p, 0) << c.name;
                for (int ch = 0; ch < 3; ++ch)
                    ASSERT_NEAR(s.weight[ch], f[ch] * std::abs(s.wi.z) / p, 1e-4f * (1 + s.weight[ch])) << c.name;
                ASSERT_NEAR(length(s.wi), 1.0f, 1e-4f) << c.name;
            }
        }
    }
}

// The coat alone and the base alone (camera paths follow the one and gather the other) are the
// two halves of the whole: their values add up to it for every pair of directions.
TEST(BsdfSampling, CoatAloneAndBaseAloneAddUpToTheWhole) {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int checked = 0;
    for (const BsdfCase& c : bsdf_cases()) {
        if (c.b.kind != bsdf::Kind::MetallicRoughness || c.b.transmission > 0 || c.b.no_diffuse || c.b.no_specular)
            continue;
        bsdf::Bsdf coat = c.b, base = c.b;
        coat.no_diffuse = true;
        base.no_specular = true;
        for (Vec3 wo : incident_directions(c.b))
            for (int i = 0; i < 500; ++i) {
                const bsdf::Sample s = bsdf::sample(c.b, wo, u(rng), u(rng), u(rng));
                if (!s.valid) continue;
                const Vec3 whole = bsdf::eval(c.b, wo, s.wi), sum = bsdf::eval(coat, wo, s.wi) + bsdf::eval(base, wo, s.wi);
                for (int ch = 0; ch < 3; ++ch) ASSERT_NEAR(sum[ch], whole[ch], 1e-5f * (1 + whole[ch])) << c.name;
                ++checked;
            }
    }
    EXPECT_GT(checked, 10000);
}

}  // namespace
}  // namespace sl::test
