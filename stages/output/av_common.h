#pragma once
// Small helpers shared by the libav encoder and decoder (internal to stages/output).
#include <string>

namespace sl {

// av_err2str for C++ (the macro uses a C compound literal).
std::string av_error_text(int err);

// libav logs go to stderr: silenced, since stderr carries our progress and the one `error:`
// line, unless the environment variable SLOWLIGHT_AV_LOG names a level. Idempotent.
void quiet_libav_logs();

}  // namespace sl
