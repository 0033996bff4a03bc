#pragma once
// What `slowlight render` derives from its options before anything renders: the options a
// render on several MPI ranks refuses, the outputs' settings, the checkpoints' settings and
// the identity their files carry. Each is a check or a translation; nothing here renders.
#include <string>

#include "config/run_options.h"
#include "config/scene_desc.h"
#include "pipeline/checkpoint.h"
#include "pipeline/frame_outputs.h"
#include "pipeline/memory_plan.h"
#include "stages/render/rank_exchange.h"
#include "stages/render/render_context.h"
#include "stages/render/section_state_io.h"

namespace sl {

// With ranks: what they do not support yet (InputError), and o.ranks set to their number.
// Without: --ranks above 1 is refused (an MPI launcher starts the ranks).
void check_rank_options(RunOptions& o, RankExchange* ex);

// --preview must name a file in an existing directory (RuntimeFailure otherwise): checked
// before rendering, since a preview that cannot be written must not stop a render.
// --gate must lie within the time window (bad input otherwise); a --phasor frequency above
// 1/(2Δ) is aliased by the frames' bins: a warning line (printed when `print`).
void check_sensor_request(const SensorRequest& sensors, const Timeline& timeline, bool print);

void check_preview_path(const std::string& path);

OutputSettings output_settings(const RunOptions& o, const SceneDesc& scene, const RenderContext& ctx,
                               const std::string& fingerprint);

// In --checkpoint DIR, or else in --exr-dir (where --resume looks anyway); none with ranks.
CheckpointSettings checkpoint_settings(const RunOptions& o, const MemoryPlan& plan);

SectionStateId section_state_id(const SceneDesc& scene, const RenderContext& ctx, const MemoryPlan& plan,
                                const std::string& fingerprint);

}  // namespace sl
