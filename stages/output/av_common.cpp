#include "stages/output/av_common.h"

extern "C" {
#include <libavutil/error.h>
#include <libavutil/log.h>
}

#include <cstdlib>
#include <mutex>

namespace sl {

std::string av_error_text(int err) {
    char buf[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(err, buf, sizeof buf);
    return buf;
}

void quiet_libav_logs() {
    static std::once_flag once;
    std::call_once(once, [] {
        // stderr carries our progress and the one `error:` line; libav's and x264's own lines
        // (x264 logs through libav) appear only when asked for: SLOWLIGHT_AV_LOG=error,
        // warning, info, verbose or debug.
        int level = AV_LOG_QUIET;
        if (const char* want = std::getenv("SLOWLIGHT_AV_LOG")) {
            const std::string w = want;
            level = w == "debug" ? AV_LOG_DEBUG : w == "verbose" ? AV_LOG_VERBOSE : w == "info" ? AV_LOG_INFO
                  : w == "warning" ? AV_LOG_WARNING : w.empty() ? AV_LOG_QUIET : AV_LOG_ERROR;
        }
        av_log_set_level(level);
    });
}

}  // namespace sl
