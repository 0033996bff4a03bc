// Checkpoints: a render killed at any moment (kill -9 included, also while a checkpoint is being
// written) and resumed, any number of times, gives output bit-identical to one that never
// stopped; a checkpoint that is not exactly this render's is refused with one `error:` line.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

#include "checkpoint_helpers.h"
#include "tests/common/video_reader.h"
#include "stages/render/section_state_io.h"

namespace sl {
namespace {

namespace fs = std::filesystem;

// Two sections, a checkpoint after every pass: one to a few seconds per whole run.
std::vector<std::string> small_render(const std::string& dir, const std::string& sub) {
    return {"render", "--width", "40", "--height", "30", "--frames", "6", "--passes", "80", "--photons", "10000",
            "--sections", "2", "--exr-dir", dir + "/" + sub, "-o", dir + "/" + sub + ".mkv", "--checkpoint-every", "0",
            "--no-progress"};
}

std::vector<std::string> checkpoints_in(const std::string& dir) {
    std::vector<std::string> out;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.path().extension() == ".ckpt") out.push_back(e.path().string());
    return out;
}

// The latest modification time among the checkpoints in `dir` (min() if there is none).
fs::file_time_type newest_checkpoint(const std::string& dir) {
    fs::file_time_type newest = fs::file_time_type::min();
    for (const std::string& p : checkpoints_in(dir)) {
        std::error_code ec;
        auto t = fs::last_write_time(p, ec);
        if (!ec && t > newest) newest = t;
    }
    return newest;
}

bool temp_checkpoint_in(const std::string& dir) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.path().filename().string().rfind(".section_", 0) == 0) return true;
    return false;
}

TEST(Checkpoints, KilledAtRandomMomentsAndResumedGivesTheSameRender) {
    const std::string dir = test::fresh_dir("kill9");
    test::RunResult ref = test::run(small_render(dir, "ref"), dir);
    ASSERT_EQ(ref.status, 0) << ref.err;

    std::mt19937 rng(12345);  // the same "random" moments every run of the test
    std::uniform_int_distribution<int> ms(0, 60);
    int kills = 0, kills_while_writing = 0, launches = 0, status = -1, continued = 0;
    bool first = true;
    while (launches < 40) {
        std::vector<std::string> args = small_render(dir, "k");
        if (!first) args.push_back("--resume");
        first = false;
        test::Child c = test::spawn(args, dir + "/err.txt");
        ++launches;
        // Every third launch is killed the moment a checkpoint's temporary file shows up.
        bool caught = false;
        if (launches % 3 == 0) {
            for (int i = 0; i < 3000 && !caught; ++i) {
                caught = fs::exists(dir + "/k") && temp_checkpoint_in(dir + "/k");
                if (!caught) std::this_thread::sleep_for(std::chrono::microseconds(200));
            }
        } else {
            // After this run's first checkpoint (so that every run moves the render on, however
            // slow the machine), a random moment: in a pass, between passes, in a write.
            const auto before = newest_checkpoint(dir + "/k");
            for (int i = 0; i < 60000 && newest_checkpoint(dir + "/k") == before; ++i)
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
            std::this_thread::sleep_for(std::chrono::milliseconds(ms(rng)));
        }
        kill(c.pid, SIGKILL);
        status = test::wait_exit(c, 60);
        continued += test::read_text(dir + "/err.txt").find("from its checkpoint at pass") != std::string::npos;
        if (status == 0) break;  // it finished before the kill
        ASSERT_EQ(status, 128 + SIGKILL) << test::read_text(dir + "/err.txt");
        ++kills;
        kills_while_writing += caught;
        if (kills >= 8) {  // enough: let it finish
            test::RunResult last = test::run(test::with(small_render(dir, "k"), {"--resume"}), dir);
            ASSERT_EQ(last.status, 0) << last.err;
            status = 0;
            break;
        }
    }
    ASSERT_EQ(status, 0);
    std::printf("%d launches, %d killed (%d while a checkpoint was being written), %d continued from one\n",
                launches, kills, kills_while_writing, continued);
    EXPECT_GE(kills, 3);
    EXPECT_GE(continued, 2) << "resumed runs must continue from a checkpoint, not start again";
    test::expect_same_exrs(dir + "/k", dir + "/ref", 6);
    VideoInfo a = read_video(dir + "/k.mkv"), b = read_video(dir + "/ref.mkv");
    EXPECT_EQ(a.frames, 6);
    EXPECT_EQ(a.mean_luma, b.mean_luma);
    EXPECT_FALSE(temp_checkpoint_in(dir + "/k"));
    EXPECT_TRUE(checkpoints_in(dir + "/k").empty()) << "a finished render keeps no checkpoint";
    fs::remove_all(dir);
}

// Killed while a checkpoint is being written (its temporary file is there, and still there
// after the kill, so the write was cut), twice, then resumed: the same render. The section is
// larger here (about 30 MB a checkpoint) so that a write lasts long enough to be caught.
TEST(Checkpoints, KilledDuringACheckpointWriteAndResumedGivesTheSameRender) {
    const std::string dir = test::fresh_dir("kill_write");
    auto args = [&](const std::string& sub) {
        return std::vector<std::string>{"render", "--width", "160", "--height", "120", "--frames", "60", "--passes", "6",
                                        "--photons", "2000", "--exr-dir", dir + "/" + sub, "--checkpoint-every", "0",
                                        "--no-progress"};
    };
    test::RunResult ref = test::run(args("ref"), dir);
    ASSERT_EQ(ref.status, 0) << ref.err;
    int cut = 0;
    for (int attempt = 0; attempt < 6 && cut < 2; ++attempt) {
        std::vector<std::string> a = args("k");
        if (attempt > 0) a.push_back("--resume");
        test::Child c = test::spawn(a, dir + "/err.txt");
        bool seen = false;
        for (int i = 0; i < 100000 && !seen; ++i) {
            seen = temp_checkpoint_in(dir + "/k");
            if (!seen) std::this_thread::sleep_for(std::chrono::microseconds(50));
        }
        kill(c.pid, SIGKILL);
        int status = test::wait_exit(c, 60);
        ASSERT_TRUE(status == 128 + SIGKILL || status == 0) << test::read_text(dir + "/err.txt");
        if (status == 0) break;
        cut += seen && temp_checkpoint_in(dir + "/k");
    }
    EXPECT_GE(cut, 1) << "no kill landed in the middle of a checkpoint write";
    test::RunResult last = test::run(test::with(args("k"), {"--resume"}), dir);
    ASSERT_EQ(last.status, 0) << last.err;
    test::expect_same_exrs(dir + "/k", dir + "/ref", 60);
    EXPECT_FALSE(temp_checkpoint_in(dir + "/k")) << "the cut write's temporary file is cleaned up";
    fs::remove_all(dir);
}

// A checkpoint of section 1 of a one-section render stopped after a few passes.
struct Saved {
    std::string dir, ckpt;
    std::vector<std::string> args;  // the render that made it (without --resume)
};

Saved interrupted_render(const std::string& name) {
    Saved s;
    s.dir = test::fresh_dir(name);
    s.args = {"render", "--width", "24", "--height", "16", "--frames", "4", "--passes", "100000", "--photons", "2000",
              "--checkpoint", s.dir + "/ck", "-o", s.dir + "/v.mkv", "--checkpoint-every", "0", "--no-progress"};
    s.ckpt = s.dir + "/ck/section_0000.ckpt";
    test::Child c = test::spawn(s.args, s.dir + "/err.txt");
    EXPECT_TRUE(test::wait_for(s.ckpt));  // a pass done: the event, not a clock
    kill(c.pid, SIGINT);
    EXPECT_EQ(test::wait_exit(c), 130) << test::read_text(s.dir + "/err.txt");
    fs::remove(s.dir + "/v.mkv");
    return s;
}

// Resuming must fail with exit 2, one `error:` line that says `why`, and no video written.
void expect_refused(const Saved& s, const std::vector<std::string>& args, const std::string& why) {
    test::RunResult r = test::run(test::with(args, {"--resume"}), s.dir);
    EXPECT_EQ(r.status, 2) << r.err;
    std::vector<std::string> errors = test::error_lines(r.err);
    ASSERT_EQ(errors.size(), 1u) << r.err;
    EXPECT_NE(errors[0].find(why), std::string::npos) << errors[0];
    EXPECT_NE(errors[0].find("section_0000.ckpt"), std::string::npos) << errors[0];
    EXPECT_FALSE(fs::exists(s.dir + "/v.mkv"));
}

std::vector<char> bytes_of(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}
void put_bytes(const std::string& path, const std::vector<char>& b) {
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(b.data(), static_cast<std::streamsize>(b.size()));
}

TEST(Checkpoints, BrokenForeignAndOtherVersionCheckpointsAreRefused) {
    Saved s = interrupted_render("refuse");
    const std::vector<char> good = bytes_of(s.ckpt);
    ASSERT_GT(good.size(), kSectionStateHeaderBytes);

    std::vector<char> b = good;
    b[b.size() / 2] ^= 0x10;  // one bit of the time buckets
    put_bytes(s.ckpt, b);
    expect_refused(s, s.args, "corrupted: its contents do not match their checksum");

    b = good;
    b[100] ^= 0x01;  // one bit of the header
    put_bytes(s.ckpt, b);
    expect_refused(s, s.args, "corrupted");

    put_bytes(s.ckpt, std::vector<char>(good.begin(), good.end() - 1000));
    expect_refused(s, s.args, "truncated");
    put_bytes(s.ckpt, std::vector<char>(good.begin(), good.begin() + 40));
    expect_refused(s, s.args, "truncated");

    b = good;
    b.insert(b.end(), 64, '\0');
    put_bytes(s.ckpt, b);
    expect_refused(s, s.args, "wrong size");

    put_bytes(s.ckpt, std::vector<char>(3000, 'x'));
    expect_refused(s, s.args, "not a slowlight checkpoint");

    b = good;
    b[8] = 7;  // the format version
    put_bytes(s.ckpt, b);
    expect_refused(s, s.args, "format version 7");

    b = good;
    b[8] = 1;  // what an older build wrote: format 1, checksums that were not XXH64
    put_bytes(s.ckpt, b);
    expect_refused(s, s.args, "written by an older slowlight (checkpoint format 1, this one reads format 3)");

    b = good;
    b[8] = 2;  // before single scattering in haze moved to the camera pass: its passes mean another estimator
    put_bytes(s.ckpt, b);
    expect_refused(s, s.args, "checkpoint format 2, this one reads format 3: single scattering in haze");

    // The same state, written by another version of the program.
    put_bytes(s.ckpt, good);
    SectionStateInfo info = read_section_state_info(s.ckpt);
    SectionLayout layout;
    layout.first_frame = 0, layout.end_frame = info.frames;
    layout.has_after = true, layout.has_before = info.slots - info.frames == 2;
    ASSERT_EQ(layout.slots(), info.slots);
    std::unique_ptr<SectionBuffer> state = load_section_state(s.ckpt, info.id, layout, false);
    SectionStateId old = info.id;
    old.program_version = "0.0.1";
    save_section_state(s.ckpt, *state, old, false);
    expect_refused(s, s.args, "written by slowlight 0.0.1");

    // Another render's checkpoint (another seed, or another size).
    put_bytes(s.ckpt, good);
    expect_refused(s, test::with(s.args, {"--seed", "2"}), "different scene or settings");
    expect_refused(s, test::with(s.args, {"--width", "32"}), "different scene or settings");

    fs::remove_all(s.dir);
}

// The first word a shell command prints ("" if it fails): xxhsum's digits, od's number.
std::string first_word_of(const std::string& command) {
    std::string out;
    if (FILE* p = popen(command.c_str(), "r")) {
        char buf[256];
        while (fgets(buf, sizeof buf, p)) out += buf;
        if (pclose(p) != 0) return "";
    }
    std::string word;
    std::istringstream(out) >> word;
    return word;
}

// docs/checkpoints.md's commands, run on a real render's checkpoint: `xxhsum -H1` (XXH64) of
// the payload and of the header prints the sums slowlight recorded at offsets 144 and 248.
TEST(Checkpoints, XxhsumReproducesTheRecordedChecksums) {
    if (std::system("command -v xxhsum >/dev/null 2>&1") != 0) GTEST_SKIP() << "xxhsum is not installed";
    Saved s = interrupted_render("xxhsum");
    const std::vector<char> file = bytes_of(s.ckpt);
    ASSERT_GT(file.size(), kSectionStateHeaderBytes);
    auto recorded = [&](size_t offset) {
        uint64_t v;
        std::memcpy(&v, file.data() + offset, 8);
        char hex[17];
        std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(v));
        return std::string(hex);
    };
    const std::string f = "'" + s.ckpt + "'";
    EXPECT_EQ(first_word_of("tail -c +257 " + f + " | xxhsum -H1"), recorded(144));
    EXPECT_EQ(first_word_of("head -c 248 " + f + " | xxhsum -H1"), recorded(248));
    EXPECT_EQ(first_word_of("od -An -tx8 -j144 -N8 " + f), recorded(144));
    EXPECT_EQ(first_word_of("od -An -tx8 -j248 -N8 " + f), recorded(248));
    EXPECT_EQ(recorded(144).size(), 16u);
    fs::remove_all(s.dir);
}

TEST(Checkpoints, AFreshRenderRefusesToOverwriteAnUnfinishedOne) {
    Saved s = interrupted_render("overwrite");
    test::RunResult r = test::run(s.args, s.dir);
    EXPECT_EQ(r.status, 2);
    std::vector<std::string> errors = test::error_lines(r.err);
    ASSERT_EQ(errors.size(), 1u) << r.err;
    EXPECT_NE(errors[0].find("--resume"), std::string::npos) << errors[0];
    EXPECT_TRUE(fs::exists(s.ckpt));
    fs::remove_all(s.dir);
}

}  // namespace
}  // namespace sl
