#include "pipeline/output_checks.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <optional>
#include <regex>

#include "config/run_options.h"
#include "config/text_util.h"
#include "foundation/errors.h"
#include "stages/output/atomic_file.h"
#include "stages/output/sensor_images.h"

namespace sl {
namespace fs = std::filesystem;
namespace {

constexpr const char* kExrNames = R"(frame_[0-9]{4,}\.exr|steady\.exr)";
constexpr const char* kPngNames = R"(frame_[0-9]{4,}\.png|steady\.png)";

// What a path is, for telling whether two paths are one file.
struct Identity {
    std::string resolved;  // links and "..": resolved as far as the path exists
    bool exists = false, regular = false;
    dev_t dev = 0;
    ino_t ino = 0;
};

Identity identify(const std::string& path) {
    Identity id;
    std::error_code ec;
    fs::path r = fs::weakly_canonical(fs::absolute(path, ec), ec);
    id.resolved = ec ? fs::absolute(path).lexically_normal().string() : r.string();
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) {
        id.exists = true;
        id.regular = S_ISREG(st.st_mode);
        id.dev = st.st_dev;
        id.ino = st.st_ino;
    }
    return id;
}

bool same_file(const Identity& a, const Identity& b) {
    if (a.exists && b.exists) return a.dev == b.dev && a.ino == b.ino;
    return a.resolved == b.resolved;
}

// A device or FIFO is written in place and may well be shared (two outputs to /dev/null).
bool streamed(const Identity& id) { return id.exists && !id.regular; }

std::string name(const OutputRequest& o) { return o.flag + " " + printable(o.path); }

[[noreturn]] void refuse(const OutputRequest& o, const std::string& why) {
    throw InputError(name(o) + ": " + why);
}

// Does writing into folder `dir` (its files named by `names`) overwrite file `f`?
bool writes_over(const OutputRequest& dir, const Identity& dir_id, const std::string& file) {
    fs::path p(file);
    Identity parent = identify(p.parent_path().empty() ? "." : p.parent_path().string());
    if (!same_file(parent, dir_id)) return false;
    return std::regex_match(p.filename().string(), std::regex(dir.names));
}

// Can a file be created in `dir`? Tried for real (permission bits say nothing to root, nor
// about a read-only mount): a probe file is made and removed at once.
std::optional<std::string> cannot_create_in(const std::string& dir) {
    std::error_code ec;
    const fs::path d = dir.empty() ? fs::path(".") : fs::path(dir);
    auto st = fs::status(d, ec);
    if (!fs::exists(st)) return "the folder '" + printable(d.string()) + "' does not exist";
    if (!fs::is_directory(st)) return "'" + printable(d.string()) + "' is not a folder";
    const std::string probe = temp_sibling((d / "write-probe").string());
    int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
        std::string why = std::strerror(errno);
        discard_file(probe);
        return "cannot create files in '" + printable(d.string()) + "': " + why;
    }
    ::close(fd);
    discard_file(probe);
    return std::nullopt;
}

void check_writable(const OutputRequest& o) {
    if (o.directory) {
        std::error_code ec;
        auto st = fs::status(o.path, ec);
        if (fs::exists(st) && !fs::is_directory(st)) refuse(o, "is not a directory");
        if (fs::exists(st)) {
            if (auto why = cannot_create_in(o.path)) refuse(o, *why);
            remove_stale_temporaries(o.path);
            return;
        }
        // Made only when rendering starts (a later input error leaves nothing behind): the
        // nearest folder that exists must take it.
        fs::path up = fs::absolute(o.path, ec).lexically_normal();
        while (!up.empty() && up != up.root_path() && !fs::exists(fs::status(up, ec))) up = up.parent_path();
        if (!fs::is_directory(fs::status(up, ec)))
            refuse(o, "cannot create the directory: '" + printable(up.string()) + "' is not a folder");
        if (auto why = cannot_create_in(up.string())) refuse(o, "cannot create the directory: " + *why);
        return;
    }
    const OutputPlace place = place_output(o.path);
    if (place.directory) refuse(o, "is a directory");
    if (place.in_place) {
        struct stat st {};
        if (::stat(o.path.c_str(), &st) == 0 && S_ISFIFO(st.st_mode)) return;  // its reader may come later
        int fd = ::open(o.path.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
        if (fd < 0) refuse(o, std::string("cannot write: ") + std::strerror(errno));
        ::close(fd);
        return;
    }
    const std::string dir = fs::path(place.path).parent_path().string();
    if (auto why = cannot_create_in(dir)) refuse(o, "cannot write: " + *why);
    remove_stale_temporaries(dir.empty() ? "." : dir);
}

}  // namespace

std::vector<OutputRequest> outputs_of(const RunOptions& o) {
    std::vector<OutputRequest> out;
    if (!o.output.empty() && o.output != "-") out.push_back({"-o", o.output, false, ""});
    if (!o.stats_path.empty()) out.push_back({"--stats", o.stats_path, false, ""});
    if (!o.cube_path.empty()) {
        out.push_back({"--cube", o.cube_path, false, ""});
        out.push_back({"--cube", o.cube_path + ".json", false, ""});  // its side-car
    }
    if (!o.hdf5_path.empty()) out.push_back({"--hdf5", o.hdf5_path, false, ""});
    if (!o.exr_dir.empty()) {
        // The sensor images go into --exr-dir too, under names of their own.
        std::string names = kExrNames;
        for (const std::string& n : SensorImages::file_names(o.sensors))
            names += "|" + std::regex_replace(n, std::regex(R"([.+])"), R"(\$&)");
        out.push_back({"--exr-dir", o.exr_dir, true, names});
    }
    if (!o.png_dir.empty()) out.push_back({"--png-dir", o.png_dir, true, kPngNames});
    return out;
}

void check_outputs(const std::vector<OutputRequest>& outputs, const std::vector<std::string>& inputs) {
    std::vector<Identity> ids;
    for (const OutputRequest& o : outputs) ids.push_back(identify(o.path));
    std::vector<Identity> in_ids;
    for (const std::string& i : inputs) in_ids.push_back(identify(i));

    for (size_t a = 0; a < outputs.size(); ++a) {
        const OutputRequest& o = outputs[a];
        for (size_t i = 0; i < inputs.size(); ++i) {
            const bool hit = o.directory ? writes_over(o, ids[a], inputs[i])
                                         : !streamed(ids[a]) && same_file(ids[a], in_ids[i]);
            if (hit)
                refuse(o, o.directory ? "would overwrite the input '" + printable(inputs[i]) + "'"
                                      : "is the input '" + printable(inputs[i]) + "'; refusing to overwrite it");
        }
        for (size_t b = 0; b < a; ++b) {
            const OutputRequest& p = outputs[b];
            bool hit = false;
            if (o.directory && p.directory) hit = false;  // different names (or the same folder, shared)
            else if (o.directory) hit = writes_over(o, ids[a], p.path);
            else if (p.directory) hit = writes_over(p, ids[b], o.path);
            else hit = !streamed(ids[a]) && same_file(ids[a], ids[b]);
            if (hit)
                refuse(o, (o.directory || p.directory ? "would write over " : "is the same file as ") + name(p) +
                              "; each output needs its own file");
        }
    }
    for (const OutputRequest& o : outputs) check_writable(o);
}

}  // namespace sl
