#include "pipeline/resume.h"

#include <cstdio>
#include <filesystem>

#include "foundation/errors.h"
#include "stages/output/exr_frame_check.h"

namespace sl {
namespace {

// True if the file is there, ours and intact; false if it is missing or fails a check (it will
// be written again, with a warning saying why); InputError if it belongs to another render.
bool ours(const std::string& path, const ExrExpectation& expect) {
    std::error_code ec;
    if (!std::filesystem::exists(std::filesystem::symlink_status(path, ec))) return false;
    try {
        read_verified_exr(path, expect);
    } catch (const RuntimeFailure& e) {
        std::fprintf(stderr, "warning: %s; rendering it again\n", e.what());
        return false;
    }
    return true;
}

}  // namespace

ExrExpectation resume_expectation(int width, int height, const std::string& fingerprint, std::optional<int> frame) {
    ExrExpectation e;
    e.width = width;
    e.height = height;
    e.fingerprint_key = kFingerprintKey;
    e.fingerprint = fingerprint;
    e.frame = frame;
    return e;
}

std::vector<bool> sections_on_disk(const FrameOutputs& outputs, const std::vector<SectionLayout>& sections,
                                   const std::string& fingerprint, int width, int height) {
    std::vector<bool> done(sections.size(), false);
    for (size_t s = 0; s < sections.size(); ++s) {
        bool all = true;
        for (int f = sections[s].first_frame; f < sections[s].end_frame; ++f)
            all = ours(outputs.exr_frame_path(f), resume_expectation(width, height, fingerprint, f)) && all;
        if (s + 1 == sections.size())
            all = ours(outputs.exr_steady_path(), resume_expectation(width, height, fingerprint, std::nullopt)) && all;
        done[s] = all;
    }
    return done;
}

}  // namespace sl
