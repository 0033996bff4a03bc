#pragma once
// --resume: which sections a previous render of the same settings already finished, judged by
// the frames it left in --exr-dir. Each EXR carries the settings' fingerprint, its frame index
// and a checksum of its pixels; a frame that fails any check is rendered again.
#include <optional>
#include <string>
#include <vector>

#include "pipeline/frame_outputs.h"
#include "stages/output/exr_frame_check.h"
#include "stages/render/section_layout.h"

namespace sl {

inline constexpr const char* kFingerprintKey = "slowlight:settings";

// What frame `frame` (nullopt: steady.exr) of this render must be on disk.
ExrExpectation resume_expectation(int width, int height, const std::string& fingerprint, std::optional<int> frame);

// done[s] is true when every frame of section s (and, for the last section, steady.exr) is on
// disk with this fingerprint and passes every check of read_verified_exr. A frame with another
// fingerprint is an InputError: frames of different scenes or settings are never mixed.
std::vector<bool> sections_on_disk(const FrameOutputs& outputs, const std::vector<SectionLayout>& sections,
                                   const std::string& fingerprint, int width, int height);

}  // namespace sl
