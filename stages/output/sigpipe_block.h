#pragma once
// Writing into a pipe whose reader is gone raises SIGPIPE, and its default action ends the
// process. How the process answers SIGPIPE belongs to the program that embeds the renderer, so
// instead of ignoring it process-wide, each stretch of code that may write to a pipe runs with
// SIGPIPE blocked in its own thread: the write then fails with EPIPE (an error the caller
// reports), and a SIGPIPE it raised is taken off the pending set before the mask is restored.
#include <signal.h>

namespace sl {

class SigpipeBlock {
public:
    SigpipeBlock() noexcept;
    ~SigpipeBlock();
    SigpipeBlock(const SigpipeBlock&) = delete;
    SigpipeBlock& operator=(const SigpipeBlock&) = delete;

private:
    sigset_t old_mask_;
    bool was_pending_ = false;  // not ours to take: it was there before we blocked
};

}  // namespace sl
