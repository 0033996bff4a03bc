#pragma once
// Runs the real `slowlight` binary as a user would: fork/exec with the given arguments, stdout
// to a file (or /dev/null), stderr captured into a string, killed after a timeout.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <string>
#include <vector>

#include "tests/test_paths.h"

namespace sl::test {

struct ProgramResult {
    int exit_code = -1;     // the exit status, or 128 + signal when killed by one
    bool timed_out = false;  // killed by run_program after the timeout
    std::string err;         // everything written to stderr

    // The lines of stderr that begin with "error:".
    std::vector<std::string> error_lines() const {
        std::vector<std::string> lines;
        size_t start = 0;
        while (start < err.size()) {
            size_t end = err.find('\n', start);
            if (end == std::string::npos) end = err.size();
            std::string line = err.substr(start, end - start);
            if (line.rfind("error:", 0) == 0) lines.push_back(line);
            start = end + 1;
        }
        return lines;
    }
};

// Runs `program` (default: the built slowlight) with `args`. Stdout goes to `stdout_path` ("" for
// /dev/null); stdin is /dev/null. Never throws: a failure to start shows as exit_code 127.
inline ProgramResult run_program(const std::vector<std::string>& args, const std::string& stdout_path = "",
                                 double timeout_seconds = 60, const std::string& program = binary()) {
    ProgramResult r;
    int err_pipe[2];
    if (::pipe2(err_pipe, O_CLOEXEC) != 0) {
        r.err = "pipe failed";
        r.exit_code = 127;
        return r;
    }
    std::vector<std::string> argv_storage;
    argv_storage.push_back(program);
    argv_storage.insert(argv_storage.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : argv_storage) argv.push_back(a.data());
    argv.push_back(nullptr);
    const std::string out = stdout_path.empty() ? "/dev/null" : stdout_path;

    pid_t pid = ::fork();
    if (pid < 0) {
        ::close(err_pipe[0]);
        ::close(err_pipe[1]);
        r.err = "fork failed";
        r.exit_code = 127;
        return r;
    }
    if (pid == 0) {  // child: only async-signal-safe calls from here on
        int in = ::open("/dev/null", O_RDONLY);
        int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (in < 0 || o < 0) ::_exit(127);
        ::dup2(in, STDIN_FILENO);
        ::dup2(o, STDOUT_FILENO);
        ::dup2(err_pipe[1], STDERR_FILENO);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    ::close(err_pipe[1]);

    using Clock = std::chrono::steady_clock;
    const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_seconds);
    char buf[4096];
    for (;;) {
        auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        if (left <= 0) {
            r.timed_out = true;
            ::kill(pid, SIGKILL);  // only the child this helper started
            break;
        }
        pollfd p{err_pipe[0], POLLIN, 0};
        int n = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1000)));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) continue;
        ssize_t got = ::read(err_pipe[0], buf, sizeof buf);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) break;  // EOF: the child closed stderr (exited)
        r.err.append(buf, static_cast<size_t>(got));
    }
    ::close(err_pipe[0]);

    // The child may keep running after closing stderr: wait for it, still up to the deadline.
    int status = 0;
    for (;;) {
        pid_t w = ::waitpid(pid, &status, r.timed_out ? 0 : WNOHANG);
        if (w == pid) break;
        if (w < 0 && errno != EINTR) break;
        if (w == 0) {
            if (Clock::now() >= deadline) {
                r.timed_out = true;
                ::kill(pid, SIGKILL);
            } else {
                ::usleep(10000);
            }
        }
    }
    if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
    else if (WIFSIGNALED(status)) r.exit_code = 128 + WTERMSIG(status);
    return r;
}

}  // namespace sl::test
