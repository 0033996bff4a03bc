#pragma once
// The process's interrupts: SIGINT and SIGTERM (and SIGUSR1, which an MPI launcher forwards for
// Ctrl-C), and, once ranks render together, the launcher's SIGTERM after a rank died. The
// handlers run on whichever thread the signal lands, at any instruction, so they touch only
// lock-free atomics and call only async-signal-safe functions (write, unlink, _exit);
// everything else (saving the section, the last lines, the exit status) happens in normal code
// that watches interrupted().
#include <atomic>

namespace sl {

// Installs the handlers. Until outputs_opened() nothing has been written, so a signal then ends
// the run at once ("interrupted during set-up; nothing written", exit 130).
void catch_interrupts(bool under_launcher);
// Whether the handlers print their lines (under MPI only rank 0 does: one line per job).
void interrupt_lines(bool print);
// From here on a signal means: end the pass in flight and deliver what you have; a second one
// quits at once, leaving no temporary file behind.
void outputs_opened();
// Under MPI the ranks agreed to start rendering: the launcher's SIGTERM now means the job ends.
void ranks_started();
bool have_ranks_started();
// Set by the first signal; what the pipeline watches.
const std::atomic<bool>& interrupted();

}  // namespace sl
