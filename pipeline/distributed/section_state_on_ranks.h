#pragma once
// Checkpoints when several ranks share the pixels: the file is the one a single process writes
// (full image, pixel order; stages/render/section_state_io.h), so a render interrupted on N
// ranks resumes on any number of ranks, or in one process, and the other way round. Only rank 0
// touches the file: the ranks' pixels come to it a chunk at a time (a few MB, never the whole
// section) and, on resume, go back out from it the same way; no other rank needs to see the
// checkpoint directory. Collectives on the Passes channel: call from the section's render.
#include <memory>
#include <string>

#include "stages/render/rank_exchange.h"
#include "stages/render/section_state_io.h"

namespace sl {

// Every rank calls it with its own buffer; rank 0 writes `path`. Returns the bytes written
// (on rank 0; 0 elsewhere). Throws RuntimeFailure on rank 0.
uint64_t save_section_state_on_ranks(RankExchange& ex, const std::string& path, const SectionBuffer& buffer,
                                     const SectionStateId& id, bool finished);

// Every rank calls it; rank 0 reads `path` (the others ignore it) and each rank gets a buffer of
// its own share of the pixels. Throws InputError on rank 0 when the file fails a check.
std::unique_ptr<SectionBuffer> load_section_state_on_ranks(RankExchange& ex, const std::string& path,
                                                           const SectionStateId& expected, const SectionLayout& layout,
                                                           bool ambient, size_t pixels);

}  // namespace sl
