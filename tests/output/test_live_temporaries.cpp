// A second Ctrl-C removes every temporary of the run before exiting, however many are live at
// once: the list a signal handler reads has no fixed size (it once stopped tracking at 64).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <string>
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

}  // namespace
