#include "pipeline/section_plan.h"

namespace sl {

std::vector<SectionLayout> plan_sections(const RenderContext& ctx, const MemoryPlan& plan, Strategy strategy) {
    std::vector<SectionLayout> out;
    for (SectionLayout l : make_sections(ctx.timeline, ctx.emission, plan.sections)) {
        if (strategy == Strategy::FrameByFrame) l.full_paths = true;
        // Constant light: a later section starts from the previous one's last frame instead of
        // gathering all earlier light again. Not with an ambient term (the carried frame would
        // hold the previous section's ambient sum too), nor for the frame-by-frame baseline,
        // whose frames are independent convergences by definition.
        l.carried = strategy == Strategy::Single && l.index > 0 && l.has_before &&
                    ctx.emission == EmissionMode::Constant && !ctx.has_ambient();
        out.push_back(l);
    }
    return out;
}

}  // namespace sl
