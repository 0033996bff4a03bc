#include "config/command_line.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "config/duration.h"
#include "config/limits.h"
#include "config/parse_scene.h"
#include "config/text_util.h"
#include "core/errors.h"

namespace sl {

namespace {

[[noreturn]] void fail(const std::string& what) {
    throw InputError("command line: " + what);
}

[[noreturn]] void bad_value(std::string_view flag, const std::string& what) {
    fail(std::string(flag) + ": " + what);
}

// An integer value; "1e5" is accepted too, as photon counts are often written that way.
int64_t integer_value(std::string_view flag, std::string_view v, int64_t lo, int64_t hi) {
    std::optional<int64_t> i = parse_whole<int64_t>(v);
    if (!i) {
        std::optional<double> d = parse_whole<double>(v);
        if (d && std::isfinite(*d) && *d == std::floor(*d) && std::abs(*d) < 9e18)
            i = static_cast<int64_t>(*d);
    }
    if (!i || *i < lo || *i > hi)
        bad_value(flag, "must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi) +
                            ", got '" + printable(v) + "'");
    return *i;
}

int int_value(std::string_view flag, std::string_view v, int lo, int hi) {
    return static_cast<int>(integer_value(flag, v, lo, hi));
}

std::string path_value(std::string_view flag, std::string_view v) {
    if (v.empty()) bad_value(flag, "must not be empty");
    return std::string(v);
}

using Apply = void (*)(RunOptions&, std::string_view flag, std::string_view value);

struct Option {
    std::string_view long_name;   // "--output"
    std::string_view short_name;  // "-o", or empty
    std::string_view value_name;  // "PATH", or empty for a flag
    std::string_view help;
    Apply apply;
};

// Every option, in --help order. Scene overrides are range-checked again by apply_overrides.
const Option kOptions[] = {
    {"--output", "-o", "PATH",
     "write the video: .mp4 (H.264), .mkv, .mov or .webm; '-' writes YUV4MPEG2 to stdout",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.output = path_value(f, v);
         r.output_given = true;
     }},
    {"--exr-dir", "", "DIR",
     "also write linear OpenEXR frames DIR/frame_0000.exr ... and DIR/steady.exr",
     [](RunOptions& r, std::string_view f, std::string_view v) { r.exr_dir = path_value(f, v); }},
    {"--png-dir", "", "DIR", "also write tone-mapped PNG frames DIR/frame_0000.png ...",
     [](RunOptions& r, std::string_view f, std::string_view v) { r.png_dir = path_value(f, v); }},
    {"--frames", "", "N", "number of frames (time.frames)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.overrides.frames = int_value(f, v, 1, limits::kMaxFrames);
     }},
    {"--passes", "", "N", "number of photon passes (render.passes)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.overrides.passes = int_value(f, v, 1, limits::kMaxPasses);
     }},
    {"--photons", "", "N", "photons per pass (render.photons_per_pass)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.overrides.photons = integer_value(f, v, 1, limits::kMaxPhotonsPerPass);
     }},
    {"--width", "", "W", "image width in pixels (camera.width)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.overrides.width = int_value(f, v, 1, limits::kMaxImageSide);
     }},
    {"--height", "", "H", "image height in pixels (camera.height)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.overrides.height = int_value(f, v, 1, limits::kMaxImageSide);
     }},
    {"--seed", "", "N", "random seed, 0..2^64-1 (render.seed)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         std::optional<uint64_t> s = parse_whole<uint64_t>(v);
         if (!s)
             bad_value(f,
                       "must be an integer in 0..18446744073709551615, got '" + printable(v) + "'");
         r.overrides.seed = *s;
     }},
    {"--sections", "", "K", "split the frames into K sections, each its own convergence",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.sections = int_value(f, v, 1, limits::kMaxSections);
     }},
    {"--max-memory", "", "SIZE",
     "pick the smallest K whose buffers fit in SIZE bytes (e.g. 512M, 2G, 1.5GiB)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.max_memory_bytes = parse_byte_size(v);
         if (!r.max_memory_bytes)
             bad_value(f,
                       "must be a size such as 1073741824, 512M, 2G or 1.5GiB (K, M, G, T are "
                       "powers of 1024), got '" +
                           printable(v) + "'");
     }},
    {"--emission", "", "MODE", "constant, pulse, or pulse:WIDTH_NS (default width: one frame)",
     [](RunOptions& r, std::string_view, std::string_view v) {
         std::string spec(v);
         parse_emission_option(spec);  // validates now, so the error comes before any work
         r.overrides.emission = spec;
     }},
    {"--camera-tof", "", "", "include the way back to the camera in the arrival time",
     [](RunOptions& r, std::string_view, std::string_view) { r.overrides.camera_tof = true; }},
    {"--no-camera-tof", "", "", "leave it out: the camera sees a photon the instant it arrives",
     [](RunOptions& r, std::string_view, std::string_view) { r.overrides.camera_tof = false; }},
    {"--strategy", "", "S",
     "single (default), or frame-by-frame: the baseline, one convergence per frame",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         if (v == "single")
             r.strategy = Strategy::Single;
         else if (v == "frame-by-frame")
             r.strategy = Strategy::FrameByFrame;
         else
             bad_value(f, "must be single or frame-by-frame, got '" + printable(v) + "'");
     }},
    {"--threads", "", "N", "worker threads (default 0: all cores)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.threads = int_value(f, v, 0, limits::kMaxThreads);
     }},
    {"--stats", "", "FILE.json", "write machine-readable run statistics to FILE.json",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.stats_path = path_value(f, v);
     }},
    {"--exposure", "", "X",
     "linear exposure multiplier > 0 for tone-mapped output (default: from steady.exr)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         std::optional<double> x = parse_whole<double>(v);
         if (!x || !std::isfinite(*x) || !(*x > 0))
             bad_value(f, "must be a finite number > 0, got '" + printable(v) + "'");
         r.exposure = *x;
     }},
    {"--cube", "", "FILE.npy",
     "also write the time-resolved stack (frames+2, height, width, RGB float32) as NumPy .npy",
     [](RunOptions& r, std::string_view f, std::string_view v) { r.cube_path = path_value(f, v); }},
    {"--resume", "", "",
     "continue an interrupted render: frames from --exr-dir, the rest from its checkpoint",
     [](RunOptions& r, std::string_view, std::string_view) { r.resume = true; }},
    {"--checkpoint", "", "DIR",
     "save the section in progress to DIR now and then and at Ctrl-C (default: --exr-dir)",
     [](RunOptions& r, std::string_view f, std::string_view v) { r.checkpoint_dir = path_value(f, v); }},
    {"--checkpoint-every", "", "TIME",
     "time between checkpoints: 90s, 20m, 2h (default 5m; 0: every pass; off: Ctrl-C only)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         if (v == "off" || v == "never") {
             r.checkpoint_every = -1.0;
             return;
         }
         std::optional<double> d = parse_duration(v);
         if (!d) bad_value(f, "must be a duration such as 90s, 20m, 2h or off, got '" + printable(v) + "'");
         r.checkpoint_every = *d;
     }},
    {"--time-limit", "", "TIME",
     "render passes until TIME (90s, 20m, 2h) is spent; --passes stays the upper bound",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         std::optional<double> d = parse_duration(v);
         if (!d || !(*d > 0))
             bad_value(f, "must be a duration > 0 such as 90s, 20m or 2h, got '" + printable(v) + "'");
         r.time_limit = *d;
     }},
    {"--preview", "", "FILE.png",
     "while rendering, a contact sheet of the section in progress, rewritten every few seconds",
     [](RunOptions& r, std::string_view f, std::string_view v) { r.preview_path = path_value(f, v); }},
    {"--no-progress", "", "", "do not show progress on stderr",
     [](RunOptions& r, std::string_view, std::string_view) { r.progress = false; }},
};

const Option* find_option(std::string_view name) {
    for (const Option& o : kOptions)
        if (name == o.long_name || (!o.short_name.empty() && name == o.short_name)) return &o;
    return nullptr;
}

// An argument that cannot be an option's value: "--x" or a short option. ("-" and "-5" can.)
bool looks_like_option(std::string_view a) {
    return a.starts_with("--") || a == "-h" || find_option(a) != nullptr;
}

}  // namespace

std::optional<uint64_t> parse_byte_size(std::string_view text) {
    size_t digits = 0;
    while (digits < text.size() &&
           (std::isdigit(static_cast<unsigned char>(text[digits])) || text[digits] == '.'))
        ++digits;
    std::string_view number = text.substr(0, digits);
    if (std::count(number.begin(), number.end(), '.') > 1 ||
        number.find_first_of("0123456789") == std::string_view::npos)
        return std::nullopt;
    std::optional<double> value = parse_whole<double>(number);
    if (!value) return std::nullopt;

    std::string unit(text.substr(digits));
    std::transform(unit.begin(), unit.end(), unit.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    double multiplier = 1;
    if (!unit.empty() && unit != "b") {
        size_t power = std::string_view("kmgt").find(unit[0]);
        std::string_view rest = std::string_view(unit).substr(1);
        if (power == std::string_view::npos || !(rest.empty() || rest == "b" || rest == "ib"))
            return std::nullopt;
        multiplier = std::ldexp(1.0, 10 * static_cast<int>(power + 1));
    }
    double bytes = std::floor(*value * multiplier);
    if (!(bytes >= 1) || bytes >= 18446744073709551615.0) return std::nullopt;
    return static_cast<uint64_t>(bytes);
}

RunOptions parse_command_line(int argc, const char* const* argv) {
    RunOptions r;
    // Help and version win over everything else on the line, even over mistakes.
    for (int i = 1; i < argc && std::string_view(argv[i]) != "--"; ++i) {
        std::string_view arg = argv[i];
        if (arg == "--help" || arg == "-h")
            r.command = RunOptions::Command::Help;
        else if (arg == "--version")
            r.command = RunOptions::Command::Version;
        else
            continue;
        return r;
    }
    bool have_command = false, have_scene = false, options_done = false;
    for (int i = 1; i < argc; ++i) {
        std::string_view arg = argv[i];
        const bool positional = options_done || arg.size() < 2 || arg[0] != '-';  // "-" too
        if (positional) {
            if (!have_command) {
                if (arg == "render")
                    r.command = RunOptions::Command::Render;
                else if (arg == "info")
                    r.command = RunOptions::Command::Info;
                else if (arg == "retime")
                    r.command = RunOptions::Command::Retime;
                else
                    fail("unknown command '" + printable(arg) +
                         "' (expected render, info or retime; see slowlight --help)");
                have_command = true;
            } else if (!have_scene) {
                if (arg.empty()) fail("the scene file name is empty");
                r.scene_path = std::string(arg);
                have_scene = true;
            } else {
                fail("two scene files given: '" + printable(r.scene_path) + "' and '" +
                     printable(arg) + "'");
            }
            continue;
        }
        if (arg == "--") {
            options_done = true;
            continue;
        }

        std::string_view name = arg, value;
        bool inline_value = false;
        if (size_t eq = arg.find('='); arg.starts_with("--") && eq != std::string_view::npos) {
            name = arg.substr(0, eq);
            value = arg.substr(eq + 1);
            inline_value = true;
        }
        const Option* opt = find_option(name);
        if (!opt) fail("unknown option '" + printable(name) + "' (see slowlight --help)");
        if (opt->value_name.empty()) {
            if (inline_value) fail(std::string(opt->long_name) + " does not take a value");
        } else if (!inline_value) {
            if (i + 1 >= argc || looks_like_option(argv[i + 1]))
                fail(std::string(opt->long_name) + " needs a value " +
                     std::string(opt->value_name));
            value = argv[++i];
        }
        opt->apply(r, opt->long_name, value);
    }
    if (!have_command) fail("no command given (expected render or info; see slowlight --help)");
    if (r.command == RunOptions::Command::Info && !have_scene)
        fail("info needs a scene file: slowlight info SCENE.json");
    if (r.command == RunOptions::Command::Retime && !have_scene)
        fail("retime needs a cube file: slowlight retime CUBE.npy -o out.mp4 [--emission ...]");
    if (r.resume && r.exr_dir.empty() && r.checkpoint_dir.empty())
        fail("--resume needs --exr-dir or --checkpoint, where the interrupted render left its state");
    return r;
}

std::string usage_text() {
    std::string s =
        "slowlight: slow-motion videos of light, rendered by transient progressive photon mapping\n"
        "\n"
        "Usage:\n"
        "  slowlight render [SCENE.json] [options]   render a scene (no scene: the built-in demo)\n"
        "  slowlight info SCENE.json [options]       scene summary and memory needed per section "
        "count\n"
        "  slowlight retime CUBE.npy [options]       make a constant or pulse video from a --cube\n"
        "                                            file without rendering again\n"
        "  slowlight --version                       print the version\n"
        "  slowlight --help, -h                      print this help (also: slowlight render "
        "--help)\n"
        "\n"
        "Options (given as --opt VALUE or --opt=VALUE; they override the scene file):\n";
    for (const Option& o : kOptions) {
        std::string names = o.short_name.empty() ? "    " : std::string(o.short_name) + ", ";
        names += std::string(o.long_name);
        if (!o.value_name.empty()) names += " " + std::string(o.value_name);
        names.resize(std::max<size_t>(names.size() + 2, 24), ' ');
        s += "  " + names + std::string(o.help) + "\n";
    }
    s += "\nTimes are in nanoseconds, lengths in meters. Exit status: 0 success, 2 invalid input,\n"
         "1 other failure, 130 interrupted.\n";
    return s;
}

}  // namespace sl
