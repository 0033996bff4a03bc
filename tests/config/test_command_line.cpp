// The command line of slowlight: commands, options, sizes, errors and --help.
#include <gtest/gtest.h>

#include <initializer_list>
#include <vector>

#include "config/command_line.h"
#include "foundation/errors.h"

using namespace sl;
using Command = RunOptions::Command;

namespace {

RunOptions parse(std::initializer_list<const char*> args) {
    std::vector<const char*> argv{"slowlight"};
    argv.insert(argv.end(), args);
    return parse_command_line(static_cast<int>(argv.size()), argv.data());
}

std::string error_of(const std::vector<const char*>& args) {
    std::vector<const char*> argv{"slowlight"};
    argv.insert(argv.end(), args.begin(), args.end());
    try {
        parse_command_line(static_cast<int>(argv.size()), argv.data());
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST(CommandLine, Commands) {
    RunOptions r = parse({"render"});
    EXPECT_EQ(r.command, Command::Render);
    EXPECT_EQ(r.scene_path, "");
    EXPECT_FALSE(r.output_given);

    r = parse({"render", "scenes/a.json"});
    EXPECT_EQ(r.scene_path, "scenes/a.json");

    r = parse({"info", "a.json"});
    EXPECT_EQ(r.command, Command::Info);
    EXPECT_EQ(r.scene_path, "a.json");

    EXPECT_EQ(parse({"--help"}).command, Command::Help);
    EXPECT_EQ(parse({"-h"}).command, Command::Help);
    EXPECT_EQ(parse({"render", "--help"}).command, Command::Help);
    EXPECT_EQ(parse({"render", "a.json", "--frames", "0", "-h"}).command, Command::Help);
    EXPECT_EQ(parse({"--version"}).command, Command::Version);
    EXPECT_EQ(parse({"--frames", "4", "render", "--", "--odd-name.json"}).scene_path,
              "--odd-name.json");
}

TEST(CommandLine, EveryOptionInBothForms) {
    for (bool with_equals : {false, true}) {
        std::vector<std::string> words;
        auto opt = [&](const char* name, const char* value) {
            if (with_equals) {
                words.push_back(std::string(name) + "=" + value);
            } else {
                words.push_back(name);
                words.push_back(value);
            }
        };
        words.push_back("render");
        opt("--output", "out.mp4");
        opt("--exr-dir", "exr");
        opt("--png-dir", "png");
        opt("--frames", "10");
        opt("--passes", "20");
        opt("--photons", "1e5");
        opt("--width", "320");
        opt("--height", "240");
        opt("--seed", "18446744073709551615");
        opt("--sections", "3");
        opt("--max-memory", "1.5G");
        opt("--emission", "pulse:2");
        opt("--strategy", "frame-by-frame");
        opt("--threads", "2");
        opt("--stats", "stats.json");
        opt("--exposure", "0.5");
        opt("--max-depth", "12");
        opt("--gltf-light-units", "radiometric");
        opt("--gltf-principled", "blender3");
        words.push_back("--camera-tof");
        words.push_back("--no-progress");
        words.push_back("scene.json");
        std::vector<const char*> argv{"slowlight"};
        for (const std::string& w : words) argv.push_back(w.c_str());
        RunOptions r = parse_command_line(static_cast<int>(argv.size()), argv.data());
        SCOPED_TRACE(with_equals ? "--opt=value" : "--opt value");
        EXPECT_EQ(r.command, Command::Render);
        EXPECT_EQ(r.scene_path, "scene.json");
        EXPECT_EQ(r.output, "out.mp4");
        EXPECT_TRUE(r.output_given);
        EXPECT_EQ(r.exr_dir, "exr");
        EXPECT_EQ(r.png_dir, "png");
        EXPECT_EQ(r.overrides.frames, 10);
        EXPECT_EQ(r.overrides.passes, 20);
        EXPECT_EQ(r.overrides.photons, 100000);
        EXPECT_EQ(r.overrides.width, 320);
        EXPECT_EQ(r.overrides.height, 240);
        EXPECT_EQ(r.overrides.seed, 18446744073709551615ull);
        EXPECT_EQ(r.sections, 3);
        EXPECT_EQ(r.max_memory_bytes, 1610612736ull);
        EXPECT_EQ(r.overrides.emission, "pulse:2");
        EXPECT_EQ(r.overrides.camera_tof, true);
        EXPECT_EQ(r.strategy, Strategy::FrameByFrame);
        EXPECT_EQ(r.threads, 2);
        EXPECT_EQ(r.stats_path, "stats.json");
        EXPECT_EQ(r.exposure, 0.5);
        EXPECT_EQ(r.overrides.max_depth, 12);
        EXPECT_EQ(r.gltf_light_units, LightUnits::Radiometric);
        EXPECT_EQ(r.gltf_principled, PrincipledBase::Blender3);
        EXPECT_FALSE(r.progress);
    }
}

TEST(CommandLine, ShortOutputAndStdout) {
    RunOptions r = parse({"render", "-o", "-"});
    EXPECT_EQ(r.output, "-");
    EXPECT_TRUE(r.output_given);
    EXPECT_EQ(r.scene_path, "");
    EXPECT_EQ(parse({"render", "--no-camera-tof"}).overrides.camera_tof, false);
    EXPECT_EQ(parse({"render"}).overrides.camera_tof, std::nullopt);
    EXPECT_EQ(parse({"render", "--frames", "3", "--frames", "5"}).overrides.frames,
              5);  // last wins
}

TEST(CommandLine, ByteSizes) {
    const std::pair<const char*, uint64_t> good[] = {
        {"1024", 1024},
        {"100B", 100},
        {"1k", 1024},
        {"1K", 1024},
        {"1KB", 1024},
        {"1kib", 1024},
        {"512M", 512ull << 20},
        {"512MiB", 512ull << 20},
        {"2G", 2ull << 30},
        {"2gb", 2ull << 30},
        {"1.5G", 1610612736ull},
        {"3T", 3ull << 40},
        {".5K", 512},
        {"0.5M", 512ull << 10},
    };
    for (auto [text, bytes] : good) EXPECT_EQ(parse_byte_size(text), bytes) << text;
    for (const char* text : {"", "0", "0.1", "-1", "1X", "1.2.3", "G", "1 G", " 1G", "1e3", "abc",
                             "1iB", "1GiBB", "16E", "99999999999T", "inf", "nan", ".", "1G "})
        EXPECT_EQ(parse_byte_size(text), std::nullopt) << "'" << text << "'";
    EXPECT_EQ(parse({"render", "--max-memory", "512M"}).max_memory_bytes, 512ull << 20);
}

TEST(CommandLine, Errors) {
    // (A vector, not an initializer_list: a list's array would not outlive this initializer.)
    const std::pair<std::vector<const char*>, const char*> cases[] = {
        {{}, "command line: no command given"},
        {{"--frames", "3"}, "command line: no command given"},
        {{"draw"}, "command line: unknown command 'draw'"},
        {{"scene.json"}, "command line: unknown command 'scene.json'"},
        {{"info"}, "command line: info needs a scene file"},
        {{"render", "a.json", "b.json"},
         "command line: two scene files given: 'a.json' and 'b.json'"},
        {{"render", ""}, "command line: the scene file name is empty"},
        {{"render", "--bogus"}, "command line: unknown option '--bogus'"},
        {{"render", "--bogus=3"}, "command line: unknown option '--bogus'"},
        {{"render", "-x"}, "command line: unknown option '-x'"},
        {{"render", "--frames"}, "command line: --frames needs a value"},
        {{"render", "--frames", "--passes", "3"}, "command line: --frames needs a value"},
        {{"render", "-o"}, "command line: --output needs a value"},
        {{"render", "-o", "--frames", "3"}, "command line: --output needs a value"},
        {{"render", "--output="}, "command line: --output: must not be empty"},
        {{"render", "--frames", "abc"},
         "command line: --frames: must be an integer in 1..100000, got 'abc'"},
        {{"render", "--frames", "0"},
         "command line: --frames: must be an integer in 1..100000, got '0'"},
        {{"render", "--frames", "2.5"}, "command line: --frames: must be an integer"},
        {{"render", "--frames", "100001"},
         "command line: --frames: must be an integer in 1..100000"},
        {{"render", "--frames", " 5"}, "command line: --frames: must be an integer"},
        {{"render", "--passes=-3"},
         "command line: --passes: must be an integer in 1..10000000, got '-3'"},
        {{"render", "--photons", "1e10"},
         "command line: --photons: must be an integer in 1..1000000000"},
        {{"render", "--width", "16385"}, "command line: --width: must be an integer in 1..16384"},
        {{"render", "--height", "0"}, "command line: --height: must be an integer in 1..16384"},
        {{"render", "--seed", "-1"},
         "command line: --seed: must be an integer in 0..18446744073709551615"},
        {{"render", "--seed", "18446744073709551616"}, "command line: --seed: must be an integer"},
        {{"render", "--sections", "0"},
         "command line: --sections: must be an integer in 1..100000"},
        {{"render", "--threads", "-1"}, "command line: --threads: must be an integer in 0..4096"},
        {{"render", "--max-memory", "lots"}, "command line: --max-memory: must be a size such as"},
        {{"render", "--max-memory", "0"}, "command line: --max-memory: must be a size such as"},
        {{"render", "--emission", "flash"},
         "command line: --emission: must be constant, pulse or pulse:WIDTH_NS"},
        {{"render", "--emission", "pulse:0"}, "command line: --emission: the pulse width must be"},
        {{"render", "--strategy", "fast"},
         "command line: --strategy: must be single or frame-by-frame, got 'fast'"},
        {{"render", "--exposure", "0"},
         "command line: --exposure: must be a finite number > 0, got '0'"},
        {{"render", "--exposure", "nan"}, "command line: --exposure: must be a finite number > 0"},
        {{"render", "--camera-tof=yes"}, "command line: --camera-tof does not take a value"},
        {{"render", "--max-depth", "0"}, "command line: --max-depth: must be an integer in 1..1000, got '0'"},
        {{"render", "--max-depth", "1001"}, "command line: --max-depth: must be an integer in 1..1000, got '1001'"},
        {{"render", "--max-depth", "deep"}, "command line: --max-depth: must be an integer in 1..1000, got 'deep'"},
        {{"render", "--gltf-light-units", "lumens"},
         "command line: --gltf-light-units: must be photometric or radiometric, got 'lumens'"},
        {{"render", "--gltf-principled", "cycles"},
         "command line: --gltf-principled: must be energy_conserving or blender3, got 'cycles'"},
        {{"render", "--no-progress=1"}, "command line: --no-progress does not take a value"},
    };
    for (const auto& [args, message] : cases) {
        std::string m = error_of(args);
        EXPECT_EQ(m.rfind(message, 0), 0u) << "expected: " << message << "\n     got: " << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
}

TEST(CommandLine, HelpListsEveryContractFlag) {
    const std::string help = usage_text();
    for (const char* flag :
         {"slowlight render", "slowlight info", "--version",      "--help",        "-o, --output",
          "--exr-dir",        "--png-dir",      "--frames",       "--passes",      "--photons",
          "--width",          "--height",       "--seed",         "--sections",    "--max-memory",
          "--emission",       "--camera-tof",   "--strategy",     "--threads",     "--stats",
          "--exposure",       "--no-progress",  "frame-by-frame", "pulse:WIDTH_NS", "--checkpoint DIR",
          "--checkpoint-every", "--time-limit", "--preview",    "--resume",      "--max-depth N",
          "--gltf-light-units U", "--gltf-principled P"})
        EXPECT_NE(help.find(flag), std::string::npos) << flag;
    // One line per option: no line longer than a wide terminal.
    size_t start = 0;
    for (size_t end; (end = help.find('\n', start)) != std::string::npos; start = end + 1)
        EXPECT_LE(end - start, 120u) << help.substr(start, end - start);
}
