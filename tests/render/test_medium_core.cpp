// The medium's pieces on their own: box clipping, transmittance, free-flight sampling (its
// weights are unbiased for RGB coefficients, also with a channel of zero extinction, and stay
// bounded when the medium is dense), Henyey-Greenstein sampling against its density, and the
// volume photons' BVH against a brute-force search.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "foundation/constants.h"
#include "core/medium.h"
#include "core/rng.h"
#include "stages/render/volume_photon_map.h"

namespace sl {
namespace {

MediumDesc desc(Vec3 sa, Vec3 ss, float g = 0) {
    MediumDesc d;
    d.present = true;
    d.sigma_a = sa;
    d.sigma_s = ss;
    d.g = g;
    d.has_bounds = true;
    d.bounds_min = Vec3(-1);
    d.bounds_max = Vec3(1);
    return d;
}

TEST(MediumCore, ClipAndTransmittance) {
    HomogeneousMedium m(desc(Vec3(0.5f), Vec3(0.5f)), Vec3(0), Vec3(0));
    float t0, t1;
    ASSERT_TRUE(m.clip({-3, 0, 0}, {1, 0, 0}, 0, 1e30f, t0, t1));
    EXPECT_FLOAT_EQ(t0, 2);
    EXPECT_FLOAT_EQ(t1, 4);
    EXPECT_FALSE(m.clip({-3, 2, 0}, {1, 0, 0}, 0, 1e30f, t0, t1));  // parallel, outside
    EXPECT_FALSE(m.clip({-3, 0, 0}, {1, 0, 0}, 0, 1.5f, t0, t1));   // stops short
    ASSERT_TRUE(m.clip({0, 0, 0}, {0, 0, -1}, 0, 0.25f, t0, t1));  // starts inside
    EXPECT_FLOAT_EQ(t0, 0);
    EXPECT_FLOAT_EQ(t1, 0.25f);
    EXPECT_NEAR(m.transmittance({-3, 0, 0}, {1, 0, 0}, 100).x, std::exp(-2.0), 1e-6);
    // No bounds: the scene's box.
    MediumDesc d = desc(Vec3(1), Vec3(0));
    d.has_bounds = false;
    HomogeneousMedium s(d, Vec3(0), Vec3(2));
    EXPECT_TRUE(s.active());
    EXPECT_NEAR(s.transmittance({-1, 1, 1}, {1, 0, 0}, 100).y, std::exp(-2.0), 1e-6);
    // Nothing to compute: no extinction, or a flat box.
    EXPECT_FALSE(HomogeneousMedium(desc(Vec3(0), Vec3(0)), Vec3(0), Vec3(1)).active());
    d.has_bounds = false;
    EXPECT_FALSE(HomogeneousMedium(d, Vec3(0), Vec3(1, 1, 0)).active());
}

// E[weight * f(event)] must equal the analytic expectation, per channel: the scattered
// weight integrates to  sigma_s (1 - e^(-st L)) / st  and the passing weight to 1... as
// expectations of the transport's two outcomes: E[w | event] P = int_0^L ss e^(-st s) ds,
// E[w | pass] P = e^(-st L).
void check_free_flight(Vec3 sa, Vec3 ss, float L) {
    HomogeneousMedium m(desc(sa, ss), Vec3(0), Vec3(0));
    Vec3 st = sa + ss;
    Rng rng(7, 99);
    const int n = 400000;
    double ev[3] = {0, 0, 0}, pass[3] = {0, 0, 0}, mean_s[3] = {0, 0, 0}, wmax = 0;
    for (int i = 0; i < n; ++i) {
        FreeFlight f = m.sample_free_flight(L, rng.uniform(), rng.uniform());
        ASSERT_TRUE(is_finite(f.weight));
        wmax = std::max<double>(wmax, max_component(f.weight));
        for (int c = 0; c < 3; ++c) {
            if (f.scattered) {
                ev[c] += f.weight[c];
                mean_s[c] += f.weight[c] * f.distance;
            } else {
                pass[c] += f.weight[c];
            }
        }
    }
    for (int c = 0; c < 3; ++c) {
        double t = st[c], want_ev = t > 0 ? ss[c] * (1 - std::exp(-t * L)) / t : ss[c] * L;
        // int_0^L s ss e^(-t s) ds
        double want_s = t > 0 ? ss[c] * (1 - std::exp(-t * L) * (1 + t * L)) / (t * t) : ss[c] * L * L / 2;
        double want_pass = std::exp(-t * L);
        EXPECT_NEAR(ev[c] / n, want_ev, 0.01 * std::max(want_ev, 0.02) + 1e-9) << "channel " << c;
        EXPECT_NEAR(mean_s[c] / n, want_s, 0.015 * std::max(want_s, 0.02) + 1e-9) << "channel " << c;
        EXPECT_NEAR(pass[c] / n, want_pass, 0.01 * std::max(want_pass, 0.02)) << "channel " << c;
    }
    EXPECT_LE(wmax, 3.0 + 1e-4);  // Tr ss / avg(st Tr) <= 3 ss/st, Tr / avg(Tr) <= 3
}

TEST(MediumCore, FreeFlightIsUnbiasedPerChannel) {
    check_free_flight(Vec3(0.1f), Vec3(0.4f), 2.0f);                              // grey
    check_free_flight({0.05f, 0.0f, 0.1f}, {0.3f, 0.15f, 0.05f}, 3.0f);            // RGB
    check_free_flight({0.2f, 0.0f, 0.0f}, {0.6f, 0.3f, 0.0f}, 2.0f);               // blue: none
    check_free_flight({2.0f, 1.0f, 0.5f}, {8.0f, 4.0f, 1.0f}, 2.0f);               // optical depth 20
}

TEST(MediumCore, DenseMediumStaysFinite) {
    HomogeneousMedium m(desc(Vec3(5), Vec3(50)), Vec3(0), Vec3(0));
    Rng rng(1, 2);
    for (int i = 0; i < 100000; ++i) {
        FreeFlight f = m.sample_free_flight(40.0f, rng.uniform(), rng.uniform());
        ASSERT_TRUE(is_finite(f.weight));
        ASSERT_LE(max_component(f.weight), 3.0f);
    }
    Vec3 tr = m.transmittance(1e6f);
    EXPECT_EQ(tr.x, 0.0f);  // underflows to 0, not NaN
}

TEST(MediumCore, HenyeyGreensteinSamplingMatchesItsDensity) {
    for (float g : {0.0f, 0.5f, -0.3f, 0.9f}) {
        HomogeneousMedium m(desc(Vec3(0), Vec3(1), g), Vec3(0), Vec3(0));
        Rng rng(3, 4);
        const Vec3 wi = normalize(Vec3(0.3f, -0.5f, 0.8f));
        const int n = 200000, bins = 8;
        double mean_cos = 0, hist[bins] = {};
        for (int i = 0; i < n; ++i) {
            Vec3 wo = m.sample_phase(wi, rng.uniform(), rng.uniform());
            ASSERT_NEAR(length(wo), 1.0f, 1e-4f);
            float c = dot(wi, wo);
            mean_cos += c;
            hist[std::min(bins - 1, static_cast<int>((c + 1) * 0.5f * bins))] += 1;
        }
        EXPECT_NEAR(mean_cos / n, g, 0.01) << "g = " << g;  // HG's mean cosine is g
        for (int b = 0; b < bins; ++b) {  // bin probability = 2 pi int p(mu) dmu
            double a = -1 + 2.0 * b / bins, e = a + 2.0 / bins, want = 0;
            for (int k = 0; k < 200; ++k) want += 2 * sl::kPiDouble * m.phase(static_cast<float>(a + (k + 0.5) * (e - a) / 200)) * (e - a) / 200;
            EXPECT_NEAR(hist[b] / n, want, 0.004 + 0.02 * want) << "g = " << g << " bin " << b;
        }
    }
}

TEST(MediumCore, BvhFindsExactlyThePhotonsNearASegment) {
    Rng rng(5, 6);
    std::vector<VolumePhoton> a, b;
    for (int i = 0; i < 30000; ++i) {
        VolumePhoton p{};
        p.x = rng.uniform() * 4 - 2; p.y = rng.uniform() * 4 - 2; p.z = rng.uniform() * 0.5f;
        if (i % 7 == 0) p.x = p.y = 0.5f;  // many equal keys
        p.depth = static_cast<uint32_t>(i);
        (i % 3 ? a : b).push_back(p);
    }
    std::vector<const std::vector<VolumePhoton>*> parts{&a, &b};
    VolumePhotonMap map;
    map.build(parts);
    ASSERT_EQ(map.size(), a.size() + b.size());
    for (int q = 0; q < 200; ++q) {
        Vec3 o{rng.uniform() * 6 - 3, rng.uniform() * 6 - 3, rng.uniform() * 2 - 1};
        Vec3 d = normalize(Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, q % 5 == 0 ? 0.0f : rng.uniform() - 0.5f));
        float len = rng.uniform() * 5, r2 = 0.01f + 0.05f * rng.uniform();
        std::vector<uint32_t> got, want;
        map.for_each_along(o, d, len, r2, [&](uint32_t i, float) { got.push_back(map.payload(i).depth); });
        for (const auto* part : parts)
            for (const VolumePhoton& p : *part) {
                Vec3 v = Vec3(p.x, p.y, p.z) - o;
                float s = dot(v, d);
                Vec3 perp = v - d * s;
                if (s >= 0 && s <= len && dot(perp, perp) < r2) want.push_back(p.depth);
            }
        std::sort(got.begin(), got.end());
        std::sort(want.begin(), want.end());
        ASSERT_EQ(got, want) << "query " << q;
    }
}

}  // namespace
}  // namespace sl
