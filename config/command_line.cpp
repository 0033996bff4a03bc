#include "config/command_line.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "config/duration.h"
#include "config/limits.h"
#include "config/nearest_name.h"
#include "config/parse_scene.h"
#include "config/sensor_options.h"
#include "config/text_util.h"
#include "foundation/errors.h"

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

// Which commands an option means something to; any other command refuses it.
enum : unsigned { kRender = 1, kInfo = 2, kRetime = 4 };

struct Option {
    unsigned commands;            // kRender | kInfo | kRetime
    std::string_view long_name;   // "--output"
    std::string_view short_name;  // "-o", or empty
    std::string_view value_name;  // "PATH", or empty for a flag
    std::string_view help;
    Apply apply;
};

// Every option, in --help order. Scene overrides are range-checked again by apply_overrides.
const Option kOptions[] = {
    {kRender | kRetime, "--output", "-o", "PATH",
     "write the video: .mp4 (H.264), .mkv, .mov or .webm; '-' writes YUV4MPEG2 to stdout",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.output = path_value(f, v);
         r.output_given = true;
     }},
    {kRender | kRetime, "--exr-dir", "", "DIR",
     "also write linear OpenEXR frames DIR/frame_0000.exr ... and DIR/steady.exr",
     [](RunOptions& r, std::string_view f, std::string_view v) { r.exr_dir = path_value(f, v); }},
    {kRender | kRetime, "--png-dir", "", "DIR",
     "also write the video's frames as PNGs DIR/frame_0000.png ... and DIR/steady.png",
     [](RunOptions& r, std::string_view f, std::string_view v) { r.png_dir = path_value(f, v); }},
    {kRender | kInfo, "--frames", "", "N", "number of frames (time.frames)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.overrides.frames = int_value(f, v, 1, limits::kMaxFrames);
     }},
    {kRender | kInfo, "--passes", "", "N", "number of photon passes (render.passes)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.overrides.passes = int_value(f, v, 1, limits::kMaxPasses);
     }},
    {kRender | kInfo, "--photons", "", "N", "photons per pass (render.photons_per_pass)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.overrides.photons = integer_value(f, v, 1, limits::kMaxPhotonsPerPass);
     }},
    {kRender | kInfo, "--max-depth", "", "N", "bounces a photon or a camera path may take, 1..1000 (render.max_depth)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.overrides.max_depth = int_value(f, v, 1, limits::kMaxDepth);
     }},
    {kRender | kInfo, "--gltf-light-units", "", "U",
     "glTF lights in photometric units (cd, lux: the default) or radiometric (W/sr, W/m^2)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         if (v == "photometric")
             r.gltf_light_units = LightUnits::Photometric;
         else if (v == "radiometric")
             r.gltf_light_units = LightUnits::Radiometric;
         else
             bad_value(f, "must be photometric or radiometric, got '" + printable(v) + "'");
     }},
    {kRender | kInfo, "--gltf-principled", "", "P",
     "glTF base: energy_conserving or blender3 (as Cycles 3.x; default for files Blender 3.x wrote)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         if (v == "energy_conserving")
             r.gltf_principled = PrincipledBase::EnergyConserving;
         else if (v == "blender3")
             r.gltf_principled = PrincipledBase::Blender3;
         else
             bad_value(f, "must be energy_conserving or blender3, got '" + printable(v) + "'");
     }},
    {kRender | kInfo, "--width", "", "W", "image width in pixels (camera.width)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.overrides.width = int_value(f, v, 1, limits::kMaxImageSide);
     }},
    {kRender | kInfo, "--height", "", "H", "image height in pixels (camera.height)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.overrides.height = int_value(f, v, 1, limits::kMaxImageSide);
     }},
    {kRender, "--seed", "", "N", "random seed, 0..2^64-1 (render.seed)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         std::optional<uint64_t> s = parse_whole<uint64_t>(v);
         if (!s)
             bad_value(f,
                       "must be an integer in 0..18446744073709551615, got '" + printable(v) + "'");
         r.overrides.seed = *s;
     }},
    {kRender, "--sections", "", "K", "split the frames into K sections, each its own convergence",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.sections = int_value(f, v, 1, limits::kMaxSections);
     }},
    {kRender | kInfo, "--max-memory", "", "SIZE",
     "keep the whole process within SIZE (e.g. 512M, 2G): the smallest K that fits",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.max_memory_bytes = parse_byte_size(v);
         if (!r.max_memory_bytes)
             bad_value(f,
                       "must be a size such as 1073741824, 512M, 2G or 1.5GiB (K, M, G, T are "
                       "powers of 1024), got '" +
                           printable(v) + "'");
     }},
    {kRender | kInfo, "--max-bucket-memory", "", "SIZE",
     "the same for the time buckets alone (the fixed part comes on top)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.max_bucket_bytes = parse_byte_size(v);
         if (!r.max_bucket_bytes)
             bad_value(f,
                       "must be a size such as 1073741824, 512M, 2G or 1.5GiB (K, M, G, T are "
                       "powers of 1024), got '" +
                           printable(v) + "'");
     }},
    {kRender | kInfo | kRetime, "--emission", "", "MODE", "constant, pulse, or pulse:WIDTH_NS (default width: one frame)",
     [](RunOptions& r, std::string_view, std::string_view v) {
         std::string spec(v);
         parse_emission_option(spec);  // validates now, so the error comes before any work
         r.overrides.emission = spec;
     }},
    {kRender | kInfo, "--camera-tof", "", "", "include the way back to the camera in the arrival time",
     [](RunOptions& r, std::string_view, std::string_view) { r.overrides.camera_tof = true; }},
    {kRender | kInfo, "--no-camera-tof", "", "", "leave it out: the camera sees a photon the instant it arrives",
     [](RunOptions& r, std::string_view, std::string_view) { r.overrides.camera_tof = false; }},
    {kRender, "--strategy", "", "S",
     "single (default), or frame-by-frame: the baseline, one convergence per frame",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         if (v == "single")
             r.strategy = Strategy::Single;
         else if (v == "frame-by-frame")
             r.strategy = Strategy::FrameByFrame;
         else
             bad_value(f, "must be single or frame-by-frame, got '" + printable(v) + "'");
     }},
    {kRender | kRetime, "--threads", "", "N", "worker threads (default 0: all cores)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.threads = int_value(f, v, 0, limits::kMaxThreads);
     }},
    {kInfo, "--ranks", "", "N",
     "memory per rank when N MPI ranks share the render (under mpirun the rank count is used)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.ranks = int_value(f, v, 1, 1 << 20);
     }},
    {kRender, "--stats", "", "FILE.json", "write machine-readable run statistics to FILE.json",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         r.stats_path = path_value(f, v);
     }},
    {kRender | kRetime, "--exposure", "", "X",
     "fixed linear exposure multiplier > 0 (default: the mean of the pixels that see no lamp)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         std::optional<double> x = parse_whole<double>(v);
         if (!x || !std::isfinite(*x) || !(*x > 0))
             bad_value(f, "must be a finite number > 0, got '" + printable(v) + "'");
         r.exposure = *x;
     }},
    {kRender, "--cube", "", "FILE.npy",
     "also write the time-resolved stack (frames+2, height, width, RGB float32) as NumPy .npy",
     [](RunOptions& r, std::string_view f, std::string_view v) { r.cube_path = path_value(f, v); }},
    {kRender, "--cube-layout", "", "ORDER",
     "slowlight (default) or mitransient: (height, width, time, 3), time in optical path length",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         if (v == "slowlight") r.cube_layout = CubeLayout::Slowlight;
         else if (v == "mitransient") r.cube_layout = CubeLayout::Mitransient;
         else bad_value(f, "must be slowlight or mitransient, got '" + printable(v) + "'");
     }},
    {kRender, "--hdf5", "", "FILE.h5",
     "also write the frames' bins as HDF5 in tal's layout (time first, t_start and delta_t in m)",
     [](RunOptions& r, std::string_view f, std::string_view v) { r.hdf5_path = path_value(f, v); }},
    {kRender, "--phasor", "", "FREQ,...",
     "write to --exr-dir a CW ToF camera's amplitude and phase per frequency (20MHz, 1.5GHz)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         FrequencyList list = parse_frequencies(v);
         if (!list.error.empty()) bad_value(f, list.error);
         r.sensors.phasor_hz = list.hz;
     }},
    {kRender, "--gate", "", "START:WIDTH",
     "also write the image a gated camera integrates from START for WIDTH ns to --exr-dir (gate.exr)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         GateWindow g = parse_gate(v);
         if (!g.error.empty()) bad_value(f, g.error);
         r.sensors.gate_start_ns = g.start_ns;
         r.sensors.gate_width_ns = g.width_ns;
     }},
    {kRender, "--first-arrival", "", "",
     "also write per pixel the time (ns) light first arrives, to --exr-dir (first_arrival.exr)",
     [](RunOptions& r, std::string_view, std::string_view) { r.sensors.first_arrival = true; }},
    {kRender, "--first-arrival-threshold", "", "X",
     "the radiance (W/sr/m^2) a frame's bin must exceed to count as an arrival (default 0)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         std::optional<double> x = parse_whole<double>(v);
         if (!x || !std::isfinite(*x) || !(*x >= 0))
             bad_value(f, "must be a finite number >= 0, got '" + printable(v) + "'");
         r.sensors.first_arrival_threshold = *x;
     }},
    {kRender, "--resume", "", "",
     "continue an interrupted render: frames from --exr-dir, the rest from its checkpoint",
     [](RunOptions& r, std::string_view, std::string_view) { r.resume = true; }},
    {kRender, "--checkpoint", "", "DIR",
     "save the section in progress to DIR now and then and at Ctrl-C (default: --exr-dir)",
     [](RunOptions& r, std::string_view f, std::string_view v) { r.checkpoint_dir = path_value(f, v); }},
    {kRender, "--checkpoint-every", "", "TIME",
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
    {kRender, "--time-limit", "", "TIME",
     "render passes until TIME (90s, 20m, 2h) is spent; --passes stays the upper bound",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         std::optional<double> d = parse_duration(v);
         if (!d || !(*d > 0))
             bad_value(f, "must be a duration > 0 such as 90s, 20m or 2h, got '" + printable(v) + "'");
         r.time_limit = *d;
     }},
    {kRender, "--preview", "", "FILE.png",
     "while rendering, a contact sheet of the section in progress, rewritten every few seconds",
     [](RunOptions& r, std::string_view f, std::string_view v) { r.preview_path = path_value(f, v); }},
    {kRender | kRetime, "--tone", "", "CURVE",
     "linear (default: clip at white), filmic (soft shoulder) or log (the darks lifted)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         if (v == "linear") r.tone = ToneCurve::Linear;
         else if (v == "filmic") r.tone = ToneCurve::Filmic;
         else if (v == "log") r.tone = ToneCurve::Log;
         else bad_value(f, "must be linear, filmic or log, got '" + printable(v) + "'");
     }},
    {kRender | kRetime, "--exposure-percentile", "", "P",
     "expose P % of the pixels that see no lamp below white (default: by their mean)",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         std::optional<double> x = parse_whole<double>(v);
         if (!x || !(*x > 0) || !(*x <= 100))
             bad_value(f, "must be a number in (0, 100], got '" + printable(v) + "'");
         r.exposure_percentile = *x;
     }},
    {kRender | kRetime, "--exposure-follow", "", "",
     "let the exposure follow the light's energy smoothly from frame to frame (for pulses)",
     [](RunOptions& r, std::string_view, std::string_view) { r.exposure_follow = true; }},
    {kRender | kRetime, "--label", "", "WHAT",
     "time: print each frame's time on the video and PNG frames",
     [](RunOptions& r, std::string_view f, std::string_view v) {
         if (v != "time") bad_value(f, "must be time, got '" + printable(v) + "'");
         r.label_time = true;
     }},
    {kRender | kRetime, "--no-progress", "", "", "do not show progress on stderr",
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

unsigned command_bit(RunOptions::Command c) {
    switch (c) {
    case RunOptions::Command::Info: return kInfo;
    case RunOptions::Command::Retime: return kRetime;
    default: return kRender;
    }
}

const char* command_name(RunOptions::Command c) {
    switch (c) {
    case RunOptions::Command::Info: return "info";
    case RunOptions::Command::Retime: return "retime";
    default: return "render";
    }
}

std::string option_lines(unsigned command) {
    std::string s;
    for (const Option& o : kOptions) {
        if (!(o.commands & command)) continue;
        std::string names = o.short_name.empty() ? "    " : std::string(o.short_name) + ", ";
        names += std::string(o.long_name);
        if (!o.value_name.empty()) names += " " + std::string(o.value_name);
        names.resize(std::max<size_t>(names.size() + 2, 24), ' ');
        s += "  " + names + std::string(o.help) + "\n";
    }
    return s;
}

}  // namespace

std::string commands_text() {
    return "slowlight: slow-motion videos of light, rendered by transient progressive photon mapping\n"
           "\n"
           "Commands:\n"
           "  slowlight render [SCENE.json] -o OUT.mp4 [options]   render a scene (no scene: the built-in demo)\n"
           "  slowlight info SCENE.json [options]                  what a scene holds, when its light arrives,\n"
           "                                                       and the memory a render needs\n"
           "  slowlight retime CUBE.npy -o OUT.mp4 [options]       a constant or pulse video from a --cube file,\n"
           "                                                       without rendering again\n"
           "  slowlight COMMAND --help                             that command's options\n"
           "  slowlight --help, --version\n"
           "\n"
           "The scene file format: docs/scene-format.md in the source tree.\n";
}

void require_an_output(const RunOptions& r) {
    // Hours of work that end nowhere help no one: ask for an output first.
    if (r.command == RunOptions::Command::Render && !r.output_given && r.exr_dir.empty() && r.png_dir.empty() &&
        r.cube_path.empty() && r.hdf5_path.empty() && r.stats_path.empty())
        fail("render writes nothing without an output: add -o out.mp4 (or --exr-dir, --png-dir, --cube, --hdf5, --stats)");
    if (r.command == RunOptions::Command::Retime && !r.output_given && r.exr_dir.empty() && r.png_dir.empty())
        fail("retime writes nothing without an output: add -o out.mp4 (or --exr-dir, --png-dir)");
}

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
        if (arg == "--help" || arg == "-h") {
            r.command = RunOptions::Command::Help;
            // `slowlight retime --help`: that command's own help.
            std::string_view first = argc > 1 ? std::string_view(argv[1]) : std::string_view();
            for (std::string_view topic : help_topics())
                if (first == topic) r.help_topic = std::string(first);
        }
        else if (arg == "--version")
            r.command = RunOptions::Command::Version;
        else
            continue;
        return r;
    }
    bool have_command = false, have_scene = false, options_done = false;
    std::vector<const Option*> given;
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
        if (!opt) {
            std::vector<std::string_view> names;
            for (const Option& o : kOptions) names.push_back(o.long_name);
            const std::string guess = nearest_name(name, names);
            fail("unknown option '" + printable(name) + "'" + (guess.empty() ? "" : ": did you mean " + guess + "?") +
                 " (see slowlight --help)");
        }
        given.push_back(opt);
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
    if (!have_command) fail("no command given (expected render, info or retime; see slowlight --help)");
    const unsigned command = command_bit(r.command);
    for (const Option* opt : given)
        if (!(opt->commands & command))
            fail(std::string(command_name(r.command)) + " does not use " + std::string(opt->long_name) +
                 " (see slowlight " + command_name(r.command) + " --help)");
    if (r.command == RunOptions::Command::Info && !have_scene)
        fail("info needs a scene file: slowlight info SCENE.json");
    if (r.command == RunOptions::Command::Retime && !have_scene)
        fail("retime needs a cube file: slowlight retime CUBE.npy -o out.mp4 [--emission ...]");
    if (r.resume && r.exr_dir.empty() && r.checkpoint_dir.empty())
        fail("--resume needs --exr-dir or --checkpoint, where the interrupted render left its state");
    if (r.sensors.any() && r.exr_dir.empty())
        fail(std::string(!r.sensors.phasor_hz.empty() ? "--phasor" : r.sensors.gate_start_ns ? "--gate" : "--first-arrival") +
             " writes its images into --exr-dir: add --exr-dir DIR");
    if (r.cube_layout != CubeLayout::Slowlight && r.cube_path.empty())
        fail("--cube-layout needs --cube FILE.npy");
    if (r.sensors.first_arrival_threshold != 0 && !r.sensors.first_arrival)
        fail("--first-arrival-threshold needs --first-arrival");
    if (r.exposure && (r.exposure_percentile || r.exposure_follow))
        fail("--exposure fixes the exposure; it cannot be combined with --exposure-percentile or --exposure-follow");
    return r;
}

std::span<const std::string_view> help_topics() {
    static constexpr std::string_view kTopics[] = {"render", "info", "retime"};
    return kTopics;
}

std::string usage_text(const std::string& topic) {
    std::string s;
    if (topic.empty()) {
        s = commands_text() +
            "\nOptions (given as --opt VALUE or --opt=VALUE; they override the scene file; each command\n"
            "refuses the ones it does not use):\n" +
            option_lines(kRender | kInfo | kRetime);
    } else if (topic == "render") {
        s = "slowlight render [SCENE.json] [options]\n"
            "  Renders the scene (no scene: the built-in Cornell box demo). At least one output is needed:\n"
            "  -o, --exr-dir, --png-dir, --cube, --hdf5 or --stats. The scene format is described in\n"
            "  docs/scene-format.md.\n\nOptions:\n" +
            option_lines(kRender);
    } else if (topic == "info") {
        s = "slowlight info SCENE.json [options]\n"
            "  Prints the scene's size, the time light needs to cross it, when the first and last direct\n"
            "  light should reach the camera, its triangles, and the memory a render needs per section\n"
            "  count K (with --max-memory SIZE: the K a render would pick). Renders nothing.\n\nOptions:\n" +
            option_lines(kInfo);
    } else {
        s = "slowlight retime CUBE.npy [options]\n"
            "  Makes a video from a cube written by `slowlight render --cube CUBE.npy`: the constant\n"
            "  emission video, or a pulse video of any whole number of frame widths, without\n"
            "  rendering again. At least one output is needed: -o, --exr-dir or --png-dir.\n\nOptions:\n" +
            option_lines(kRetime);
    }
    s += "\nTimes are in nanoseconds, lengths in meters. Exit status: 0 success, 2 invalid input,\n"
         "1 other failure, 130 interrupted.\n";
    return s;
}

}  // namespace sl
