#pragma once
// --resume: which sections a previous render of the same settings already finished, judged by
// the frames it left in --exr-dir (each EXR carries the settings' fingerprint).
#include <string>
#include <vector>

#include "pipeline/frame_outputs.h"
#include "stages/render/section_layout.h"

namespace sl {

// done[s] is true when every frame of section s (and, for the last section, steady.exr) is on
// disk with this fingerprint. A frame with another fingerprint is an InputError: frames of
// different scenes or settings are never mixed.
std::vector<bool> sections_on_disk(const FrameOutputs& outputs, const std::vector<SectionLayout>& sections,
                                   const std::string& fingerprint);

inline constexpr const char* kFingerprintKey = "slowlight:settings";

}  // namespace sl
