#pragma once
// --resume with checkpoints: which section continues from which checkpoint, every checkpoint
// in the directory checked first (a checkpoint of other settings, of another version, cut short
// or corrupted is an InputError, never trusted). Without --resume, a directory that holds a
// checkpoint is refused, so that forgetting --resume never throws a long render away.
#include <string>
#include <vector>

#include "pipeline/frame_outputs.h"
#include "stages/render/section_layout.h"
#include "stages/render/section_state_io.h"

namespace sl {

struct SectionStart {
    bool from_checkpoint = false;
    int passes_done = 0;
    bool finished = false;  // the checkpoint holds the section's final state: only its frames are left
    std::string path;
};

// One entry per section. `id` is this render's identity (its section field is ignored).
std::vector<SectionStart> checkpoints_to_resume(const std::string& dir, const SectionStateId& id,
                                                const std::vector<SectionLayout>& sections, bool ambient);

// InputError when `dir` holds a checkpoint (a fresh render would overwrite it).
void refuse_existing_checkpoints(const std::string& dir, const std::string& resume_command);

// EXR frames written at an interrupt carry "slowlight:interrupted" = "1": such a section is
// not finished even though all its frames are on disk. Clears on_disk[s] for those.
void drop_interrupted_sections(const FrameOutputs& outputs, const std::vector<SectionLayout>& sections,
                               std::vector<bool>& on_disk);

inline constexpr const char* kPassesKey = "slowlight:passes";
inline constexpr const char* kInterruptedKey = "slowlight:interrupted";

}  // namespace sl
