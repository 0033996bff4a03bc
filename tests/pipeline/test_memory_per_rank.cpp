// Memory scales out: with N MPI ranks each holds the buckets of 1/N of the pixels, `info
// --ranks N` says so, and --max-memory (a budget per rank) picks K for the ranks running.
#include <gtest/gtest.h>

#include <map>
#include <sstream>

#include "tests/pipeline/mpi_launcher.h"
#include "tests/pipeline/pipeline_helpers.h"

namespace sl::test {
namespace {

// info's table: K -> exact bytes ("(123 bytes)").
std::map<int, uint64_t> info_bytes(const ScratchDir& dir, const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"info", sample("cornell_box.json")};
    args.insert(args.end(), extra.begin(), extra.end());
    ProgramResult r = run_program(args, dir.file("info.txt"));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::map<int, uint64_t> by_k;
    std::istringstream lines(read_text(dir.file("info.txt")));
    std::string line;
    bool table = false;
    while (std::getline(lines, line)) {
        if (line.find("sections K") != std::string::npos) { table = true; continue; }
        if (!table) continue;
        std::istringstream f(line);
        int k = 0;
        if (!(f >> k)) break;
        size_t open = line.find('('), bytes = line.find(" bytes)");
        if (open == std::string::npos || bytes == std::string::npos) break;
        by_k[k] = std::stoull(line.substr(open + 1, bytes - open - 1));
    }
    return by_k;
}

}  // namespace

TEST(MemoryPerRank, InfoWithRanksDividesTheBucketsByTheRankCount) {
    ScratchDir dir;
    // The sample is 256x256: 4096 tiles of 16 pixels, 1024 per rank on 4 ranks, so every
    // per-pixel byte (buckets, radius, photon count) divides by exactly 4.
    std::map<int, uint64_t> one = info_bytes(dir, {}), four = info_bytes(dir, {"--ranks", "4"});
    for (int k : {1, 2, 4, 8}) {
        ASSERT_TRUE(one.count(k) && four.count(k)) << "K = " << k;
        EXPECT_EQ(four[k] * 4, one[k]) << "K = " << k;
    }
    ProgramResult r = run_program({"render", "--ranks", "2", "--no-progress"});
    EXPECT_EQ(r.exit_code, 2) << "--ranks outside mpirun is for info: " << r.err;
}

TEST(MemoryPerRank, MaxBucketMemoryUnderMpirunIsABudgetPerRank) {
    if (find_mpirun().empty()) GTEST_SKIP() << "no mpirun on the PATH";
    ScratchDir dir;
    std::map<int, uint64_t> two = info_bytes(dir, {"--ranks", "2", "--frames", "8"});
    ASSERT_TRUE(two.count(1));
    // A budget that holds K = 1 on each of two ranks, but not one rank's whole image.
    const std::vector<std::string> args = {"render", sample("cornell_box.json"), "--frames", "8", "--passes", "1",
                                           "--photons", "1000", "--no-progress", "--max-bucket-memory",
                                           std::to_string(two[1])};
    auto with_stats = [&](std::vector<std::string> a, const std::string& name) {
        a.insert(a.end(), {"--stats", dir.file(name)});
        return a;
    };
    ProgramResult alone = run_program(with_stats(args, "one.json"));
    ASSERT_EQ(alone.exit_code, 0) << alone.err;
    ProgramResult ranks = run_ranks(2, with_stats(args, "two.json"));
    ASSERT_EQ(ranks.exit_code, 0) << ranks.err;
    nlohmann::json s1 = read_json(dir.file("one.json")), s2 = read_json(dir.file("two.json"));
    EXPECT_GT(s1["sections"].get<int>(), 1);
    EXPECT_EQ(s2["sections"].get<int>(), 1);
    EXPECT_EQ(s2["ranks"].get<int>(), 2);
    EXPECT_EQ(s2["buffer_bytes_per_section"].get<uint64_t>(), two[1]);
}

}  // namespace sl::test
