#pragma once
// Runs the real program as a child process: arguments, exit status, stderr, optional signals.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/test_paths.h"

namespace sl::test {

struct Child {
    pid_t pid = -1;
    std::string stderr_path;
};

// Stdout to `stdout_fd` (e.g. a pipe's end) when it is not negative, else to `stdout_path`.
inline Child spawn(const std::vector<std::string>& args, const std::string& stderr_path,
                   const std::string& stdout_path = "/dev/null", int stdout_fd = -1) {
    Child c;
    c.stderr_path = stderr_path;
    c.pid = fork();
    if (c.pid == 0) {
        int err = open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int out = stdout_fd >= 0 ? stdout_fd : open(stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(err, 2);
        dup2(out, 1);
        std::vector<char*> argv;
        std::string bin = binary();
        argv.push_back(bin.data());
        std::vector<std::string> copy = args;
        for (auto& a : copy) argv.push_back(a.data());
        argv.push_back(nullptr);
        execv(bin.c_str(), argv.data());
        _exit(127);
    }
    return c;
}

// Exit status (or 128 + signal), waiting at most `timeout_s` seconds (then kills: -1).
inline int wait_exit(const Child& c, double timeout_s = 300) {
    auto t0 = std::chrono::steady_clock::now();
    int status = 0;
    for (;;) {
        pid_t r = waitpid(c.pid, &status, WNOHANG);
        if (r == c.pid) break;
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > timeout_s) {
            kill(c.pid, SIGKILL);
            waitpid(c.pid, &status, 0);
            return -1;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    return 128 + WTERMSIG(status);
}

inline std::string read_text(const std::string& path) {
    std::ifstream f(path);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

struct RunResult {
    int status = -1;
    std::string err;
};

inline RunResult run(const std::vector<std::string>& args, const std::string& work_dir, double timeout_s = 300) {
    std::string err_path = work_dir + "/stderr.txt";
    Child c = spawn(args, err_path);
    RunResult r;
    r.status = wait_exit(c, timeout_s);
    r.err = read_text(err_path);
    return r;
}

// Lines of `text` that begin with "error:".
inline std::vector<std::string> error_lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (line.rfind("error:", 0) == 0) out.push_back(line);
    return out;
}

// A fresh, empty directory for one test.
inline std::string fresh_dir(const std::string& name) {
    auto dir = std::filesystem::temp_directory_path() / ("slowlight_robustness_" + name + "_" + std::to_string(getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir.string();
}

}  // namespace sl::test
