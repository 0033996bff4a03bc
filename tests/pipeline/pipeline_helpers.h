#pragma once
// Shared helpers for the tests that run the real program: a scratch directory, the program's
// common small settings, and readers for what it writes (EXR means, --stats JSON).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "stages/output/exr_io.h"
#include "tests/common/temp_dir.h"
#include "tests/pipeline/run_program.h"
#include "tests/test_paths.h"

namespace sl::test {

using ScratchDir = TempDir;

inline std::string sample(const std::string& name) {
    return (std::filesystem::path(source_dir()) / "samples" / name).string();
}

inline std::vector<std::string> sample_scenes() {
    std::vector<std::string> found;
    for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(source_dir()) / "samples"))
        if (e.path().extension() == ".json") found.push_back(e.path().string());
    std::sort(found.begin(), found.end());
    return found;
}

inline std::string frame_name(int k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.exr", k);
    return name;
}

// Mean over pixels and channels of an EXR image; also reports whether every value is finite.
struct ExrSummary {
    int width = 0, height = 0;
    double mean = 0;
    bool finite = true;
    std::vector<float> rgb;
};

inline ExrSummary summarize_exr(const std::string& path) {
    ExrImage img = read_exr(path);
    ExrSummary s;
    s.width = img.width;
    s.height = img.height;
    double sum = 0;
    for (float v : img.rgb) {
        if (!std::isfinite(v)) s.finite = false;
        else sum += v;
    }
    s.mean = img.rgb.empty() ? 0 : sum / static_cast<double>(img.rgb.size());
    s.rgb = std::move(img.rgb);
    return s;
}

// Means of DIR/frame_0000.exr ... DIR/frame_{F-1}.exr.
inline std::vector<double> frame_means(const std::string& dir, int frames) {
    std::vector<double> means;
    for (int k = 0; k < frames; ++k) means.push_back(summarize_exr(dir + "/" + frame_name(k)).mean);
    return means;
}

inline nlohmann::json read_json(const std::string& path) {
    std::ifstream f(path);
    if (!f) throw std::runtime_error("cannot open " + path);
    return nlohmann::json::parse(f);
}

inline std::string read_text(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

// The small, quick settings every render in these tests shares (32x32, few passes/photons),
// followed by `extra`.
inline std::vector<std::string> small_render(const std::string& scene, std::vector<std::string> extra,
                                             int frames = 4, int passes = 2, int photons = 2000,
                                             int width = 32, int height = 32) {
    std::vector<std::string> a{"render"};
    if (!scene.empty()) a.push_back(scene);
    const std::vector<std::string> common{"--frames", std::to_string(frames), "--passes", std::to_string(passes),
                                          "--photons", std::to_string(photons), "--width", std::to_string(width),
                                          "--height", std::to_string(height), "--no-progress"};
    a.insert(a.end(), common.begin(), common.end());
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
}

// Spearman rank correlation (ties get their average rank).
inline double rank_correlation(const std::vector<double>& a, const std::vector<double>& b) {
    auto ranks = [](const std::vector<double>& v) {
        std::vector<size_t> idx(v.size());
        for (size_t i = 0; i < v.size(); ++i) idx[i] = i;
        std::sort(idx.begin(), idx.end(), [&](size_t x, size_t y) { return v[x] < v[y]; });
        std::vector<double> r(v.size());
        for (size_t i = 0; i < idx.size();) {
            size_t j = i;
            while (j + 1 < idx.size() && v[idx[j + 1]] == v[idx[i]]) ++j;
            for (size_t k = i; k <= j; ++k) r[idx[k]] = (static_cast<double>(i + j)) / 2.0;
            i = j + 1;
        }
        return r;
    };
    std::vector<double> ra = ranks(a), rb = ranks(b);
    const double n = static_cast<double>(a.size());
    double ma = 0, mb = 0;
    for (size_t i = 0; i < ra.size(); ++i) ma += ra[i] / n, mb += rb[i] / n;
    double sab = 0, saa = 0, sbb = 0;
    for (size_t i = 0; i < ra.size(); ++i) {
        sab += (ra[i] - ma) * (rb[i] - mb);
        saa += (ra[i] - ma) * (ra[i] - ma);
        sbb += (rb[i] - mb) * (rb[i] - mb);
    }
    return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 0.0;
}

}  // namespace sl::test

// Prints the command's stderr with a failed expectation about it.
#define SL_EXPECT_EXIT(result, code)                                                           \
    EXPECT_EQ((result).exit_code, (code)) << "timed out: " << (result).timed_out << "\nstderr:\n" \
                                          << (result).err
