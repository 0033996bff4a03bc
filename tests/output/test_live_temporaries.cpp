// A second Ctrl-C removes every temporary of the run before exiting, however many are live at
// once: the list a signal handler reads has no fixed size (it once stopped tracking at 64).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "stages/output/atomic_file.h"
#include "stages/output/live_temporaries.h"
#include "tests/common/temp_dir.h"

namespace {

// In a child process (the clean-up ends the process): 200 temporaries, 100 of them then
// committed, 50 more made afterwards (reusing what the committed ones were tracked in).
TEST(LiveTemporaries, AllAreRemovedBeyondSixtyFour) {
    sl::test::TempDir dir;
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        std::vector<std::string> temps;
        auto make = [&](int k) {
            const std::string final_name = dir.file("out_" + std::to_string(k) + ".bin");
            const std::string temp = sl::temp_sibling(final_name);
            std::ofstream(temp) << k;
            temps.push_back(temp);
            return final_name;
        };
        for (int k = 0; k < 200; ++k) make(k);
        for (int k = 0; k < 100; ++k) sl::commit_file(temps[size_t(k)], dir.file("out_" + std::to_string(k) + ".bin"));
        for (int k = 200; k < 250; ++k) make(k);
        sl::remove_live_temporaries_and_exit(0);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
    int committed = 0, left = 0;
    for (const std::string& name : dir.entries()) {
        if (name.rfind(sl::kTempPrefix, 0) == 0) ++left;
        else ++committed;
    }
    EXPECT_EQ(left, 0) << "temporaries left behind";
    EXPECT_EQ(committed, 100) << "committed files must stay";
}

// Several threads making and committing temporaries at once (the output writers do): nodes
// freed by one thread are taken by another, and still every live one is removed and no
// committed file is touched.
TEST(LiveTemporaries, ThreadsMakingAndCommittingAtOnce) {
    sl::test::TempDir dir;
    constexpr int kThreads = 4, kEach = 300;
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        std::vector<std::thread> threads;
        for (int t = 0; t < kThreads; ++t)
            threads.emplace_back([&, t] {
                for (int k = 0; k < kEach; ++k) {
                    const std::string final_name = dir.file("t" + std::to_string(t) + "_" + std::to_string(k));
                    const std::string temp = sl::temp_sibling(final_name);
                    std::ofstream(temp) << k;
                    if (k % 2 == 0) sl::commit_file(temp, final_name);  // every other one stays live
                }
            });
        for (std::thread& t : threads) t.join();
        sl::remove_live_temporaries_and_exit(0);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
    int committed = 0, left = 0;
    for (const std::string& name : dir.entries()) {
        if (name.rfind(sl::kTempPrefix, 0) == 0) ++left;
        else ++committed;
    }
    EXPECT_EQ(left, 0) << "temporaries left behind";
    EXPECT_EQ(committed, kThreads * kEach / 2);
}

}  // namespace
