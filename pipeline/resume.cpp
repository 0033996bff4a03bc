#include "pipeline/resume.h"

#include <filesystem>

#include "core/errors.h"
#include "stages/output/exr_io.h"

namespace sl {
namespace {

// True if the file is there and ours; false if it is missing or unreadable (it will be
// written again); InputError if it belongs to another render.
bool ours(const std::string& path, const std::string& fingerprint) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return false;
    ExrImage img;
    try {
        img = read_exr(path);
    } catch (const RuntimeFailure&) {
        return false;
    }
    auto it = img.metadata.find(kFingerprintKey);
    if (it == img.metadata.end() || it->second != fingerprint)
        throw InputError("--resume: " + path +
                         " was rendered from a different scene or settings (fingerprint " +
                         (it == img.metadata.end() ? std::string("missing") : it->second) + ", this render " +
                         fingerprint + "); use another --exr-dir or remove it");
    return true;
}

}  // namespace

std::vector<bool> sections_on_disk(const FrameOutputs& outputs, const std::vector<SectionLayout>& sections,
                                   const std::string& fingerprint) {
    std::vector<bool> done(sections.size(), false);
    for (size_t s = 0; s < sections.size(); ++s) {
        bool all = true;
        for (int f = sections[s].first_frame; f < sections[s].end_frame; ++f)
            all = ours(outputs.exr_frame_path(f), fingerprint) && all;
        if (s + 1 == sections.size()) all = ours(outputs.exr_steady_path(), fingerprint) && all;
        done[s] = all;
    }
    return done;
}

}  // namespace sl
