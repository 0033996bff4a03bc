#include "pipeline/section_plan.h"

namespace sl {

std::vector<SectionLayout> plan_sections(const RenderContext& ctx, const MemoryPlan& plan, Strategy strategy) {
    std::vector<SectionLayout> out;
    for (SectionLayout l : make_sections(ctx.timeline, ctx.scene.emission.mode, plan.sections)) {
        if (strategy == Strategy::FrameByFrame) l.full_paths = true;
        out.push_back(l);
    }
    return out;
}

}  // namespace sl
