#pragma once
// --resume on several ranks: only rank 0 looks at the checkpoint directory and at --exr-dir
// (the other ranks may not even see them); it judges which section continues from where, the
// ranks agree to go on (or all stop with rank 0's error line and status), and every rank gets
// the same answer.
#include <functional>
#include <vector>

#include "pipeline/resume_checkpoints.h"
#include "stages/render/rank_exchange.h"

namespace sl {

// `judge` runs on rank 0 only and may throw (InputError: status 2, else 1). Returns 0, or the
// status every rank then exits with. A checkpoint's path is known on rank 0 only.
int share_resume_plan(RankExchange& ex, const std::function<void(std::vector<SectionStart>&, std::vector<bool>&)>& judge,
                      std::vector<SectionStart>& starts, std::vector<bool>& on_disk);

}  // namespace sl
