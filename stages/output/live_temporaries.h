#pragma once
// The temporaries this process has not yet committed or discarded, kept where a signal handler
// can read them: a second Ctrl-C must remove every one of them before it exits, however many
// are live. Normal code records and forgets them (allocating as needed); the handler only walks
// what is published and calls unlink(2), then _exit(2).
#include <cstdint>
#include <string>

namespace sl {

// Records `path` under `id` (unique per process) as a live temporary. Normal code only.
void remember_temporary(uint64_t id, const std::string& path);

// The temporary `id` is committed or discarded: an exit no longer removes it. Never throws.
void forget_temporary(uint64_t id) noexcept;

// Removes every live temporary and ends the process with `status`. Async-signal-safe (unlink,
// _exit): meant for a signal handler. Any other thread that records a temporary from then on
// waits for the exit, so that no file appears behind the scan.
[[noreturn]] void remove_live_temporaries_and_exit(int status) noexcept;

}  // namespace sl
