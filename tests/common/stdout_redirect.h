#pragma once
// Points file descriptor 1 somewhere else for the lifetime of the object (tests of what is
// written to stdout). No gtest assertion may run meanwhile, since gtest prints failures to
// stdout.
#include <unistd.h>

#include <cstdio>

namespace sl::test {

class StdoutRedirect {
public:
    explicit StdoutRedirect(int fd) {
        std::fflush(stdout);
        saved_ = ::dup(1);
        ::dup2(fd, 1);
    }
    ~StdoutRedirect() {
        std::fflush(stdout);
        ::dup2(saved_, 1);
        ::close(saved_);
    }
    StdoutRedirect(const StdoutRedirect&) = delete;
    StdoutRedirect& operator=(const StdoutRedirect&) = delete;

private:
    int saved_ = -1;
};

}  // namespace sl::test
