#include "stages/output/sigpipe_block.h"

#include <pthread.h>

#include <cerrno>
#include <ctime>

namespace sl {

namespace {

sigset_t only_sigpipe() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGPIPE);
    return set;
}

}  // namespace

SigpipeBlock::SigpipeBlock() noexcept {
    const sigset_t pipe = only_sigpipe();
    sigset_t pending;
    sigemptyset(&pending);
    sigpending(&pending);  // a SIGPIPE can be pending only where it was already blocked
    was_pending_ = sigismember(&pending, SIGPIPE) == 1;
    pthread_sigmask(SIG_BLOCK, &pipe, &old_mask_);
}

SigpipeBlock::~SigpipeBlock() {
    const int saved_errno = errno;  // the caller may still look at the write's errno
    if (!was_pending_) {
        // A write to a pipe sends SIGPIPE to the writing thread: take it, if there is one.
        const sigset_t pipe = only_sigpipe();
        const timespec now{0, 0};
        while (sigtimedwait(&pipe, nullptr, &now) < 0 && errno == EINTR) {
        }
    }
    pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);
    errno = saved_errno;
}

}  // namespace sl
