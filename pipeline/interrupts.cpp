#include "pipeline/interrupts.h"

#include <unistd.h>

#include <cerrno>
#include <csignal>

#include "stages/output/live_temporaries.h"

namespace sl {
namespace {

// What the handlers read and write: lock-free atomics only (interrupts.h says why).
std::atomic<bool> g_cancel{false};
// Until outputs are opened nothing has been written, so a signal then ends the run at once.
std::atomic<bool> g_setting_up{true};
// Under MPI a launcher passes an interrupt to every rank: only rank 0 says so (one line per job).
std::atomic<bool> g_signal_lines{true};
// Under MPI: the ranks agreed to start rendering (a launcher's SIGTERM then means the job ends).
std::atomic<bool> g_ranks_started{false};
static_assert(std::atomic<bool>::is_always_lock_free, "read by signal handlers");

void say_from_handler(const char* text, size_t size) {
    const int saved_errno = errno;  // the interrupted code may be about to read it
    ssize_t ignored = write(STDERR_FILENO, text, size);
    (void)ignored;
    errno = saved_errno;
}

extern "C" void on_signal(int) {
    if (g_setting_up.load()) {
        static const char msg[] = "slowlight: interrupted during set-up; nothing written\n";
        if (g_signal_lines.load()) say_from_handler(msg, sizeof msg - 1);
        _exit(130);
    }
    // A second signal: stop at once, leaving no temporary behind (files already committed stay).
    if (g_cancel.exchange(true)) remove_live_temporaries_and_exit(130);
    static const char msg[] = "\nslowlight: interrupted: ending the pass in flight, then saving the section and "
                              "writing its frames (interrupt again to quit at once)\n";
    if (g_signal_lines.load()) say_from_handler(msg, sizeof msg - 1);
}

// Under MPI the launcher stops every rank with SIGTERM when one of them died: say so, from
// rank 0, as the job's one error line (a rank blocked in a collective would never get to it).
// The outputs are incomplete and stay so: their temporaries go.
extern "C" void on_launcher_signal(int sig) {
    if (!g_ranks_started.load() || g_cancel.load()) {
        if (g_cancel.exchange(true)) remove_live_temporaries_and_exit(130);
        return;
    }
    if (g_signal_lines.load()) {  // rank 0, cached before: no call into the exchange from here
        static const char msg[] = "error: the MPI launcher stopped this render (another rank has died or was killed); "
                                  "its outputs are incomplete\n";
        say_from_handler(msg, sizeof msg - 1);
    }
    remove_live_temporaries_and_exit(128 + sig);
}

}  // namespace

void catch_interrupts(bool under_launcher) {
    g_setting_up = true;
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    // Ctrl-C to Open MPI's mpirun cannot reach the ranks (it stops them with SIGTERM, as when a
    // rank died, and exits 1); SIGUSR1 it forwards: under MPI that is the interrupt of Ctrl-C.
    if (under_launcher) std::signal(SIGUSR1, on_signal);
}

void interrupt_lines(bool print) { g_signal_lines = print; }
void outputs_opened() { g_setting_up = false; }

void ranks_started() {
    g_ranks_started = true;
    std::signal(SIGTERM, on_launcher_signal);
}

bool have_ranks_started() { return g_ranks_started.load(); }
const std::atomic<bool>& interrupted() { return g_cancel; }

}  // namespace sl
