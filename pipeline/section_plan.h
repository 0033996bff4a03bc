#pragma once
// The sections a render is cut into: K sections of the timeline (MemoryPlan), each a
// convergence of its own (with constant light, a section after the first starts from the last
// frame of the one before: SectionLayout::carried); the frame-by-frame baseline makes every
// frame a full, independent convergence with full photon paths, as the paper does.
#include <vector>

#include "config/run_options.h"
#include "pipeline/memory_plan.h"
#include "stages/render/render_context.h"
#include "stages/render/section_layout.h"

namespace sl {

std::vector<SectionLayout> plan_sections(const RenderContext& ctx, const MemoryPlan& plan, Strategy strategy);

}  // namespace sl
