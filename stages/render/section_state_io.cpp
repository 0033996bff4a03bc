#include "stages/render/section_state_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <utility>
#include <vector>

#include "foundation/xxh64.h"
#include "foundation/errors.h"

namespace sl {
namespace {

constexpr char kMagic[8] = {'S', 'L', 'C', 'H', 'K', 'P', 'T', '\n'};
constexpr size_t kTile = SectionBuffer::kTile;
constexpr size_t kChunkTiles = 4096;  // pixels converted and written per step: 64 Ki

// Header fields at fixed offsets (little-endian, as the machines that run this are).
struct Header {
    char magic[8];
    uint32_t format, header_bytes;
    char version[32], fingerprint[32];
    int32_t section, sections, passes_done, passes_target, finished;
    int32_t width, height, slots, frames, ambient;
    double max_radius, volume_radius2;
    uint64_t payload_bytes, payload_checksum;
};
static_assert(sizeof(Header) + 8 <= kSectionStateHeaderBytes);
// Where docs/checkpoints.md tells a user to find the sums that `xxhsum -H1` reproduces.
static_assert(offsetof(Header, format) == 8 && offsetof(Header, payload_checksum) == 144);

void put_text(char (&dst)[32], const std::string& s) {
    std::memset(dst, 0, sizeof dst);
    std::memcpy(dst, s.data(), std::min(s.size(), sizeof dst - 1));
}
std::string get_text(const char (&src)[32]) { return std::string(src, strnlen(src, sizeof src)); }

uint64_t header_checksum(const unsigned char* bytes) {
    Xxh64 c;
    c.update(bytes, kSectionStateHeaderBytes - 8);
    return c.value();
}

uint64_t payload_bytes_of(size_t pixels, int slots, bool ambient) {
    return pixels * (2 * sizeof(double) + (ambient ? 3 * sizeof(float) : 0) + slots * 3 * sizeof(float));
}

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
    throw InputError("checkpoint " + path + ": " + why);
}

// A hidden sibling, unique to this process: "<dir>/.<name>.tmp<pid>".
std::string temp_name(const std::string& path) {
    std::filesystem::path p(path);
    return (p.parent_path() / ("." + p.filename().string() + ".tmp" + std::to_string(::getpid()))).string();
}

class File {
public:
    File(int fd) : fd_(fd) {}
    ~File() {
        if (fd_ >= 0) ::close(fd_);
    }
    int fd() const { return fd_; }
    int release() { return std::exchange(fd_, -1); }

private:
    int fd_;
};

void write_all(int fd, const void* data, size_t n, const std::string& path) {
    auto* p = static_cast<const char*>(data);
    while (n > 0) {
        ssize_t w = ::write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) throw RuntimeFailure("checkpoint " + path + ": cannot write: " + std::strerror(errno));
        p += w, n -= static_cast<size_t>(w);
    }
}

// Reads exactly n bytes; false at the end of the file.
bool read_all(int fd, void* data, size_t n) {
    auto* p = static_cast<char*>(data);
    while (n > 0) {
        ssize_t r = ::read(fd, p, n);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) return false;
        p += r, n -= static_cast<size_t>(r);
    }
    return true;
}

// Walks the payload in file order, a chunk of whole tiles at a time: for each array, calls
// io(pointer to the file-order bytes, byte count, fill) where `fill` copies the chunk from
// (writing) or into (reading) the buffer. Shared by save, load and verify so that the three
// can never disagree on the layout.
template <class Io>
void walk_payload(size_t pixels, bool ambient, Io&& io) {
    const size_t tiles = (pixels + kTile - 1) / kTile;
    for (int array = 0; array < 4; ++array) {
        if (array == 2 && !ambient) continue;
        for (size_t t0 = 0; t0 < tiles; t0 += kChunkTiles) {
            size_t p0 = t0 * kTile, p1 = std::min(pixels, (t0 + kChunkTiles) * kTile);
            io(array, p0, p1);
        }
    }
}

}  // namespace

uint64_t save_section_state_from(const std::string& path, const SectionStateId& id, const SectionStateScalars& v,
                                 bool finished, const SectionStateFill& fill) {
    const size_t pixels = v.pixels;
    const bool ambient = v.ambient;
    const int slots = v.slots;
    const std::string temp = temp_name(path);
    File f(::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644));
    if (f.fd() < 0) throw RuntimeFailure("checkpoint " + path + ": cannot create: " + std::strerror(errno));
    try {
        unsigned char head[kSectionStateHeaderBytes] = {};
        write_all(f.fd(), head, sizeof head, path);  // filled in at the end
        Xxh64 sum;
        std::vector<char> stage;
        walk_payload(pixels, ambient, [&](int array, size_t p0, size_t p1) {
            stage.resize((p1 - p0) * section_state_pixel_bytes(array, slots));
            fill(array, p0, p1, stage.data());
            sum.update(stage.data(), stage.size());
            write_all(f.fd(), stage.data(), stage.size(), path);
        });
        Header h{};
        std::memcpy(h.magic, kMagic, 8);
        h.format = kSectionStateFormat;
        h.header_bytes = kSectionStateHeaderBytes;
        put_text(h.version, id.program_version);
        put_text(h.fingerprint, id.fingerprint);
        h.section = id.section, h.sections = id.sections;
        h.passes_done = v.passes_done, h.passes_target = id.passes_target, h.finished = finished;
        h.width = id.width, h.height = id.height, h.slots = slots, h.frames = v.frames;
        h.ambient = ambient;
        h.max_radius = v.max_radius, h.volume_radius2 = v.volume_radius2;
        h.payload_bytes = payload_bytes_of(pixels, slots, ambient);
        h.payload_checksum = sum.value();
        std::memcpy(head, &h, sizeof h);
        uint64_t hc = header_checksum(head);
        std::memcpy(head + kSectionStateHeaderBytes - 8, &hc, 8);
        if (::pwrite(f.fd(), head, sizeof head, 0) != static_cast<ssize_t>(sizeof head) || ::fsync(f.fd()) != 0)
            throw RuntimeFailure("checkpoint " + path + ": cannot write: " + std::strerror(errno));
        if (::close(f.release()) != 0)
            throw RuntimeFailure("checkpoint " + path + ": cannot write: " + std::strerror(errno));
        if (std::rename(temp.c_str(), path.c_str()) != 0)
            throw RuntimeFailure("checkpoint " + path + ": cannot rename into place: " + std::strerror(errno));
        // The rename itself must reach the disk before the checkpoint counts as written.
        std::string dir = std::filesystem::path(path).parent_path().string();
        int d = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        if (d >= 0) {
            ::fsync(d);
            ::close(d);
        }
        return kSectionStateHeaderBytes + h.payload_bytes;
    } catch (...) {
        ::unlink(temp.c_str());
        throw;
    }
}

SectionStateScalars section_state_scalars(const SectionBuffer& b) {
    SectionStateScalars v;
    v.pixels = b.radius2.size();
    v.slots = b.slots;
    v.frames = b.layout.frames();
    v.ambient = !b.ambient.empty();
    v.passes_done = b.passes_done;
    v.max_radius = b.max_radius;
    v.volume_radius2 = b.volume_radius2;
    return v;
}

void copy_section_state_chunk(const SectionBuffer& b, int array, size_t p0, size_t p1, char* out) {
    const size_t n = p1 - p0;
    if (array == 0 || array == 1) {
        const double* src = (array == 0 ? b.radius2.data() : b.photon_count.data()) + p0;
        std::memcpy(out, src, n * sizeof(double));
    } else if (array == 2) {
        std::memcpy(out, b.ambient.data() + 3 * p0, n * 3 * sizeof(float));
    } else {
        float* dst = reinterpret_cast<float*>(out);
        for (size_t p = p0; p < p1; ++p)
            for (int s = 0; s < b.slots; ++s, dst += 3) std::memcpy(dst, b.slot(p, s), 3 * sizeof(float));
    }
}

void take_section_state_chunk(SectionBuffer& b, int array, size_t p0, size_t p1, const char* src) {
    const size_t n = p1 - p0;
    if (array == 0) std::memcpy(b.radius2.data() + p0, src, n * sizeof(double));
    if (array == 1) std::memcpy(b.photon_count.data() + p0, src, n * sizeof(double));
    if (array == 2) std::memcpy(b.ambient.data() + 3 * p0, src, n * 3 * sizeof(float));
    if (array == 3) {
        const float* in = reinterpret_cast<const float*>(src);
        for (size_t p = p0; p < p1; ++p)
            for (int s = 0; s < b.slots; ++s, in += 3) std::memcpy(b.slot(p, s), in, 3 * sizeof(float));
    }
}

uint64_t save_section_state(const std::string& path, const SectionBuffer& b, const SectionStateId& id, bool finished) {
    return save_section_state_from(path, id, section_state_scalars(b), finished,
                                   [&](int array, size_t p0, size_t p1, char* out) {
                                       copy_section_state_chunk(b, array, p0, p1, out);
                                   });
}

size_t section_state_pixel_bytes(int array, int slots) {
    return array < 2 ? sizeof(double) : array == 2 ? 3 * sizeof(float) : static_cast<size_t>(slots) * 3 * sizeof(float);
}

void for_each_section_state_chunk(size_t pixels, bool ambient, const std::function<void(int, size_t, size_t)>& fn) {
    walk_payload(pixels, ambient, fn);
}

namespace {

struct Opened {
    int fd = -1;
    Header h{};
    uint64_t file_bytes = 0;
};

Opened open_checked(const std::string& path, File& file) {
    Opened o;
    o.fd = file.fd();
    if (o.fd < 0) refuse(path, std::string("cannot open: ") + std::strerror(errno));
    struct stat st {};
    if (::fstat(o.fd, &st) != 0 || !S_ISREG(st.st_mode)) refuse(path, "not a regular file");
    o.file_bytes = static_cast<uint64_t>(st.st_size);
    unsigned char head[kSectionStateHeaderBytes] = {};
    size_t got = static_cast<size_t>(std::min<uint64_t>(o.file_bytes, sizeof head));
    if (!read_all(o.fd, head, got) || std::memcmp(head, kMagic, std::min<size_t>(got, 8)) != 0 || got < 8)
        refuse(path, "not a slowlight checkpoint");
    if (got < sizeof head)
        refuse(path, "truncated: " + std::to_string(o.file_bytes) + " bytes, shorter than its header");
    std::memcpy(&o.h, head, sizeof o.h);
    uint64_t hc;
    std::memcpy(&hc, head + kSectionStateHeaderBytes - 8, 8);
    if (o.h.format < kSectionStateFormat)  // 1: a hand-written checksum; 2: single scattering by photons
        refuse(path, "written by an older slowlight (checkpoint format " + std::to_string(o.h.format) +
                         ", this one reads format " + std::to_string(kSectionStateFormat) +
                         (o.h.format == 2 ? ": single scattering in haze is now computed in the camera pass, not by "
                                            "photons; finish it with that version or start again)"
                                          : ")"));
    if (o.h.format != kSectionStateFormat)
        refuse(path, "format version " + std::to_string(o.h.format) + ", this program reads version " +
                         std::to_string(kSectionStateFormat));
    if (hc != header_checksum(head)) refuse(path, "corrupted: its header's checksum does not match");
    return o;
}

SectionStateInfo info_of(const Header& h) {
    SectionStateInfo i;
    i.id.program_version = get_text(h.version);
    i.id.fingerprint = get_text(h.fingerprint);
    i.id.section = h.section, i.id.sections = h.sections, i.id.passes_target = h.passes_target;
    i.id.width = h.width, i.id.height = h.height;
    i.format = h.format;
    i.passes_done = h.passes_done;
    i.finished = h.finished != 0;
    i.slots = h.slots, i.frames = h.frames, i.ambient = h.ambient != 0;
    i.payload_bytes = h.payload_bytes;
    return i;
}

// Everything but the payload's checksum.
void check_header(const std::string& path, const Opened& o, const SectionStateId& e, const SectionLayout& layout,
                  bool ambient) {
    const Header& h = o.h;
    if (get_text(h.version) != e.program_version)
        refuse(path, "written by slowlight " + get_text(h.version) + ", this is slowlight " + e.program_version +
                         "; finish it with that version or start again");
    if (get_text(h.fingerprint) != e.fingerprint)
        refuse(path, "saved from a different scene or settings (fingerprint " + get_text(h.fingerprint) +
                         ", this render " + e.fingerprint + ")");
    if (h.section != e.section || h.sections != e.sections)
        refuse(path, "holds section " + std::to_string(h.section + 1) + " of " + std::to_string(h.sections) +
                         ", expected section " + std::to_string(e.section + 1) + " of " + std::to_string(e.sections));
    if (h.width != e.width || h.height != e.height || h.slots != layout.slots() || h.frames != layout.frames() ||
        (h.ambient != 0) != ambient || h.passes_target != e.passes_target)
        refuse(path, "holds " + std::to_string(h.width) + "x" + std::to_string(h.height) + " pixels with " +
                         std::to_string(h.slots) + " time slots, this render needs " + std::to_string(e.width) + "x" +
                         std::to_string(e.height) + " with " + std::to_string(layout.slots()));
    if (h.passes_done < 0 || h.passes_done > h.passes_target) refuse(path, "corrupted: impossible pass count");
    const uint64_t payload = payload_bytes_of(static_cast<size_t>(e.width) * e.height, layout.slots(), ambient);
    const uint64_t want = kSectionStateHeaderBytes + payload;
    if (h.payload_bytes != payload) refuse(path, "corrupted: its header gives the wrong payload size");
    if (o.file_bytes < want)
        refuse(path, "truncated: " + std::to_string(o.file_bytes) + " bytes, a whole one has " + std::to_string(want));
    if (o.file_bytes > want)
        refuse(path, "wrong size: " + std::to_string(o.file_bytes) + " bytes, a whole one has " + std::to_string(want));
}

// Reads the payload chunk by chunk; `take(array, p0, p1, bytes)` keeps what it wants.
template <class Take>
void read_payload(const std::string& path, const Opened& o, size_t pixels, int slots, bool ambient, Take&& take) {
    Xxh64 sum;
    std::vector<char> stage;
    walk_payload(pixels, ambient, [&](int array, size_t p0, size_t p1) {
        const size_t n = p1 - p0;
        stage.resize(n * section_state_pixel_bytes(array, slots));
        if (!read_all(o.fd, stage.data(), stage.size())) refuse(path, "truncated while reading");
        sum.update(stage.data(), stage.size());
        take(array, p0, p1, stage.data());
    });
    if (sum.value() != o.h.payload_checksum) refuse(path, "corrupted: its contents do not match their checksum");
}

}  // namespace

SectionStateInfo read_section_state_info(const std::string& path) {
    File f(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
    return info_of(open_checked(path, f).h);
}

SectionStateInfo verify_section_state(const std::string& path, const SectionStateId& expected,
                                      const SectionLayout& layout, bool ambient) {
    File f(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
    Opened o = open_checked(path, f);
    check_header(path, o, expected, layout, ambient);
    read_payload(path, o, static_cast<size_t>(expected.width) * expected.height, layout.slots(), ambient,
                 [](int, size_t, size_t, const char*) {});
    return info_of(o.h);
}

SectionStateInfo load_section_state_into(const std::string& path, const SectionStateId& expected,
                                         const SectionLayout& layout, bool ambient, const SectionStateTake& take,
                                         SectionStateScalars* scalars) {
    File f(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
    Opened o = open_checked(path, f);
    check_header(path, o, expected, layout, ambient);
    const size_t pixels = static_cast<size_t>(expected.width) * expected.height;
    read_payload(path, o, pixels, layout.slots(), ambient, take);
    if (scalars) {
        scalars->pixels = pixels;
        scalars->slots = layout.slots();
        scalars->frames = layout.frames();
        scalars->ambient = ambient;
        scalars->passes_done = o.h.passes_done;
        scalars->max_radius = o.h.max_radius;
        scalars->volume_radius2 = o.h.volume_radius2;
    }
    return info_of(o.h);
}

std::unique_ptr<SectionBuffer> load_section_state(const std::string& path, const SectionStateId& expected,
                                                  const SectionLayout& layout, bool ambient, SectionStateInfo* info) {
    const size_t pixels = static_cast<size_t>(expected.width) * expected.height;
    auto b = std::make_unique<SectionBuffer>(pixels, layout, 0.0f, ambient);
    SectionStateScalars v;
    SectionStateInfo i = load_section_state_into(
        path, expected, layout, ambient,
        [&](int array, size_t p0, size_t p1, const char* src) { take_section_state_chunk(*b, array, p0, p1, src); }, &v);
    b->passes_done = v.passes_done;
    b->max_radius = v.max_radius;
    b->volume_radius2 = v.volume_radius2;
    if (info) *info = i;
    return b;
}

}  // namespace sl
