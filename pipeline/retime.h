#pragma once
// `slowlight retime CUBE.npy`: the constant video, or a pulse video of any width that is a
// multiple of the bucket width, made from a saved transient cube without rendering again.
#include "config/run_options.h"

namespace sl {
int retime(const RunOptions& options);  // exit status; throws InputError / RuntimeFailure
}  // namespace sl
