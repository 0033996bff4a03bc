#include "pipeline/resume_checkpoints.h"

#include <cstdlib>
#include <filesystem>

#include "foundation/errors.h"
#include "pipeline/checkpoint.h"
#include "stages/output/exr_io.h"

namespace sl {

std::vector<SectionStart> checkpoints_to_resume(const std::string& dir, const SectionStateId& id,
                                                const std::vector<SectionLayout>& sections, bool ambient) {
    std::vector<SectionStart> out(sections.size());
    remove_stale_checkpoint_temps(dir);
    for (const std::string& path : checkpoint_files(dir)) {
        const std::string name = std::filesystem::path(path).filename().string();
        const int index = std::atoi(name.c_str() + 8);  // section_NNNN.ckpt
        SectionStateId want = id;
        want.section = index;
        if (index >= static_cast<int>(sections.size())) {
            SectionStateInfo info = read_section_state_info(path);
            throw InputError("checkpoint " + path + ": saved from a different scene or settings (section " +
                             std::to_string(index + 1) + " of " + std::to_string(info.id.sections) + ", fingerprint " +
                             info.id.fingerprint + "; this render has " + std::to_string(sections.size()) +
                             " section(s), fingerprint " + id.fingerprint + "); remove it or use another directory");
        }
        SectionStateInfo info;
        try {
            info = verify_section_state(path, want, sections[index], ambient);
        } catch (const InputError& e) {
            throw InputError(std::string(e.what()) + "; remove it to render that section again");
        }
        out[index] = SectionStart{true, info.passes_done, info.finished, path};
    }
    return out;
}

void refuse_existing_checkpoints(const std::string& dir, const std::string& resume_command) {
    std::vector<std::string> found = checkpoint_files(dir);
    if (found.empty()) return;
    std::string what = found.front();
    try {
        SectionStateInfo info = read_section_state_info(found.front());
        what += " (section " + std::to_string(info.id.section + 1) + " of " + std::to_string(info.id.sections) +
                ", " + std::to_string(info.passes_done) + " passes)";
    } catch (const InputError&) {
    }
    throw InputError("checkpoint " + what + " holds an unfinished render; continue it with --resume (" +
                     resume_command + ") or remove it to start again");
}

void drop_interrupted_sections(const FrameOutputs& outputs, const std::vector<SectionLayout>& sections,
                               std::vector<bool>& on_disk) {
    for (size_t s = 0; s < sections.size() && s < on_disk.size(); ++s) {
        if (!on_disk[s]) continue;
        try {
            ExrImage first = read_exr(outputs.exr_frame_path(sections[s].first_frame), outputs.frame_size());
            auto it = first.metadata.find(kInterruptedKey);
            if (it != first.metadata.end() && it->second == "1") on_disk[s] = false;
        } catch (const RuntimeFailure&) {
            on_disk[s] = false;
        }
    }
}

}  // namespace sl
