#include "stages/output/exr_header_scan.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <vector>

#include "foundation/errors.h"

namespace sl {

namespace {

std::string label_for(const std::string& path, const std::string& label) {
    return label.empty() ? "cannot read EXR '" + path + "'" : label;
}

// Version field flags (OpenEXR file layout, "version field").
constexpr uint32_t kTiledFlag = 0x200, kNonImageFlag = 0x800, kMultiPartFlag = 0x1000;

// A cursor over the header's bytes; every read is bounds-checked.
class HeaderBytes {
public:
    HeaderBytes(std::vector<char> bytes, std::string label) : b_(std::move(bytes)), label_(std::move(label)) {}
    [[noreturn]] void fail(const std::string& what) const { throw RuntimeFailure(label_ + ": " + what); }
    size_t at() const { return at_; }
    size_t size() const { return b_.size(); }
    bool at_end_marker() {
        if (at_ >= b_.size()) fail("the header has no end");
        if (b_[at_] != 0) return false;
        ++at_;
        return true;
    }
    std::string cstring(size_t limit) {
        const size_t start = at_;
        while (at_ < limit && b_[at_] != 0) ++at_;
        if (at_ >= limit || at_ - start > 255) fail("a name in the header runs past its end");
        return std::string(&b_[start], at_++ - start);
    }
    template <typename T>
    T value(size_t limit) {
        if (at_ + sizeof(T) > limit) fail("a header value runs past its end");
        T v;
        std::memcpy(&v, &b_[at_], sizeof(T));
        at_ += sizeof(T);
        return v;
    }
    std::string text(size_t end) {
        const std::string t(b_.data() + at_, b_.data() + end);
        at_ = end;
        return t;
    }
    void skip_to(size_t pos) { at_ = pos; }

private:
    std::vector<char> b_;
    std::string label_;
    size_t at_ = 0;
};

std::vector<char> head_of(const std::string& path, size_t& file_size) {
    std::ifstream f(path, std::ios::binary | std::ios::ate);
    const std::streamoff end = f ? static_cast<std::streamoff>(f.tellg()) : 0;
    file_size = end > 0 ? static_cast<size_t>(end) : 0;
    // Our headers are a few hundred bytes; 64 KiB is plenty.
    std::vector<char> bytes(std::min<size_t>(file_size, size_t(1) << 16));
    f.seekg(0);
    if (!bytes.empty() && !f.read(bytes.data(), static_cast<std::streamsize>(bytes.size())))
        throw RuntimeFailure("cannot read EXR '" + path + "'");
    return bytes;
}

// The channel list: only R, G, B, each half or float, sampled at every pixel.
std::map<std::string, std::string> read_channels(HeaderBytes& h, size_t end) {
    std::map<std::string, std::string> seen;
    while (h.at() < end) {
        if (h.at_end_marker()) break;
        const std::string name = h.cstring(end);
        const int32_t type = h.value<int32_t>(end);
        h.value<uint32_t>(end);  // pLinear and reserved bytes
        const int32_t xs = h.value<int32_t>(end), ys = h.value<int32_t>(end);
        if ((name != "R" && name != "G" && name != "B") || !seen.emplace(name, type == 1 ? "half" : "float").second)
            h.fail("channel '" + name + "' is not one of R, G, B written once");
        if (type != 1 && type != 2) h.fail("channel '" + name + "' is neither half nor float");
        if (xs != 1 || ys != 1) h.fail("channel '" + name + "' is subsampled");
    }
    if (h.at() != end) h.fail("its channel list does not end where its size says");
    return seen;
}

}  // namespace

ExrHeaderInfo scan_exr_header(const std::string& path, const std::string& label) {
    size_t file_size = 0;
    HeaderBytes h(head_of(path, file_size), label_for(path, label));
    const size_t n = h.size();
    if (n < 8 || h.value<uint32_t>(n) != 20000630u) h.fail("not an OpenEXR file");
    const uint32_t version = h.value<uint32_t>(n);
    if ((version & 0xff) != 2) h.fail("OpenEXR version " + std::to_string(version & 0xff) + ", not 2");
    if (version & (kTiledFlag | kNonImageFlag | kMultiPartFlag))
        h.fail("tiled, deep or multi-part: not a frame written by this program");

    ExrHeaderInfo info;
    std::set<std::string> names;
    while (!h.at_end_marker()) {
        const std::string name = h.cstring(n), type = h.cstring(n);
        const int32_t size = h.value<int32_t>(n);
        if (size < 0 || static_cast<size_t>(size) > n - h.at())
            h.fail("header attribute '" + name + "' runs past " + (n < file_size ? "64 KiB" : "the file"));
        if (!names.insert(name).second) h.fail("header attribute '" + name + "' appears twice");
        const size_t end = h.at() + static_cast<size_t>(size);
        if (name == "dataWindow" || name == "displayWindow") {
            if (type != "box2i" || size != 16) h.fail(name + " is not a box2i");
            int* w = name == "dataWindow" ? &info.data_x0 : &info.display_x0;
            for (int i = 0; i < 4; ++i) w[i] = h.value<int32_t>(end);
        } else if (name == "channels") {
            if (type != "chlist") h.fail("channels is not a chlist");
            info.channels = read_channels(h, end);
        } else if (name == "tiles" || name == "type" || name == "chunkCount") {
            h.fail("header attribute '" + name + "': not a scanline frame written by this program");
        } else if (type == "string") {
            info.metadata[name] = h.text(end);
        }
        h.skip_to(end);
    }
    if (info.channels.empty() || !names.count("dataWindow") || !names.count("displayWindow") ||
        !names.count("compression"))
        h.fail("its header lacks channels, a window or a compression");
    return info;
}

void require_exr_size(const std::string& path, const ExrHeaderInfo& h, ExrSize want, const std::string& label) {
    auto fail = [&](const std::string& what) { throw RuntimeFailure(label_for(path, label) + ": " + what); };
    const int64_t w = int64_t(h.data_x1) - h.data_x0 + 1, ht = int64_t(h.data_y1) - h.data_y0 + 1;
    const bool same = h.data_x0 == h.display_x0 && h.data_y0 == h.display_y0 && h.data_x1 == h.display_x1 &&
                      h.data_y1 == h.display_y1;
    if (want.width > 0 || want.height > 0) {
        if (!same || h.data_x0 != 0 || h.data_y0 != 0 || w != want.width || ht != want.height)
            fail("its data window " + std::to_string(w) + " x " + std::to_string(ht) + " at (" +
                 std::to_string(h.data_x0) + ", " + std::to_string(h.data_y0) + ") (display window " +
                 std::to_string(int64_t(h.display_x1) - h.display_x0 + 1) + " x " +
                 std::to_string(int64_t(h.display_y1) - h.display_y0 + 1) + ") is not this render's " +
                 std::to_string(want.width) + " x " + std::to_string(want.height) + " at (0, 0)");
    } else if (w <= 0 || ht <= 0 || w > kMaxExrWidth || w * ht > kMaxExrPixels) {
        fail("its window of " + std::to_string(w) + " x " + std::to_string(ht) + " pixels is empty or too large");
    }
}

}  // namespace sl
