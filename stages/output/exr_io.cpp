#include "stages/output/exr_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <Imath/half.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <vector>

#include "core/errors.h"
#include "stages/output/atomic_file.h"

namespace sl {

namespace {

constexpr const char* kChannels[3] = {"R", "G", "B"};

[[noreturn]] void fail(const char* what, const std::string& path, const std::exception& e) {
    throw RuntimeFailure(one_line(std::string(what) + " '" + path + "': " + e.what()));
}

// Interleaved RGB of element type T: three slices into one buffer.
template <typename T>
Imf::FrameBuffer interleaved(Imf::PixelType type, const T* data, const Imath::Box2i& window) {
    constexpr size_t px = 3 * sizeof(T);
    const size_t row = px * size_t(window.max.x - window.min.x + 1);
    Imf::FrameBuffer fb;
    for (int c = 0; c < 3; ++c)
        fb.insert(kChannels[c], Imf::Slice::Make(type, data + c, window, px, row));
    return fb;
}

}  // namespace

void write_exr(const std::string& path, int w, int h, const float* rgb,
               const std::map<std::string, std::string>& metadata, bool half) {
    if (w <= 0 || h <= 0)
        throw RuntimeFailure("cannot write EXR '" + path + "': empty image");
    const std::string temp = temp_sibling(path);
    try {
        Imf::Header header(w, h);
        const Imf::PixelType type = half ? Imf::HALF : Imf::FLOAT;
        // Monte Carlo noise fills a float's low mantissa bits, which no lossless coder shrinks:
        // ZIP saved 3 % of a 256x256 frame's bytes and took 10x the time of writing it plain
        // (docs/benchmarks.md). Halves keep ZIP, which does shrink them.
        header.compression() = half ? Imf::ZIP_COMPRESSION : Imf::NO_COMPRESSION;
        for (const char* name : kChannels) header.channels().insert(name, Imf::Channel(type));
        for (const auto& [key, value] : metadata) header.insert(key, Imf::StringAttribute(value));

        std::vector<Imath::half> halves;
        Imf::FrameBuffer fb;
        if (half) {
            halves.assign(rgb, rgb + size_t(w) * size_t(h) * 3);  // half(float) rounds
            fb = interleaved(Imf::HALF, halves.data(), header.dataWindow());
        } else {
            fb = interleaved(Imf::FLOAT, rgb, header.dataWindow());
        }
        // Scoped so the file is closed (fully flushed) before the rename.
        {
            Imf::OutputFile out(temp.c_str(), header);
            out.setFrameBuffer(fb);
            out.writePixels(h);
        }
    } catch (const std::exception& e) {
        discard_file(temp);
        fail("cannot write EXR", path, e);
    }
    commit_file(temp, path);
}

ExrImage read_exr(const std::string& path) {
    try {
        Imf::InputFile in(path.c_str());
        const Imf::Header& header = in.header();
        const Imath::Box2i window = header.dataWindow();

        ExrImage img;
        img.width = window.max.x - window.min.x + 1;
        img.height = window.max.y - window.min.y + 1;
        img.rgb.assign(size_t(img.width) * size_t(img.height) * 3, 0.0f);
        in.setFrameBuffer(interleaved(Imf::FLOAT, img.rgb.data(), window));
        in.readPixels(window.min.y, window.max.y);

        for (auto it = header.begin(); it != header.end(); ++it)
            if (auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
                img.metadata[it.name()] = s->value();
        return img;
    } catch (const std::exception& e) {
        fail("cannot read EXR", path, e);
    }
}

namespace {

// OpenEXR sizes its tables from the header before any check of ours can run: a forged file that
// declares a huge attribute or data window makes the library allocate gigabytes. So the header is
// walked here first, in the file's own bytes: every attribute must fit in the file, and the data
// window must be one that a file of this size could hold (at least 8 bytes of offset table per
// scanline). Found by fuzzing --resume's reader.
void check_header_fits_file(const std::string& path) {
    std::ifstream f(path, std::ios::binary | std::ios::ate);
    const std::streamoff end = f ? static_cast<std::streamoff>(f.tellg()) : 0;
    const size_t file_size = end > 0 ? static_cast<size_t>(end) : 0;
    // The header is at the start and small: read at most 1 MiB of it.
    std::vector<char> bytes(std::min<size_t>(file_size, size_t(1) << 20));
    f.seekg(0);
    if (!bytes.empty() && !f.read(bytes.data(), static_cast<std::streamsize>(bytes.size())))
        throw RuntimeFailure("cannot read EXR '" + path + "'");
    const size_t n = bytes.size();
    auto bad = [&](const std::string& what) { throw RuntimeFailure("cannot read EXR '" + path + "': " + what); };
    if (n < 8 || static_cast<unsigned char>(bytes[0]) != 0x76 || bytes[1] != 0x2f || bytes[2] != 0x31 || bytes[3] != 0x01)
        bad("not an OpenEXR file");
    size_t at = 8;
    auto cstring = [&]() {
        const size_t start = at;
        while (at < n && bytes[at] != 0) ++at;
        if (at >= n || at - start > 255) bad("a header attribute's name or type runs past the file");
        ++at;
        return std::string(&bytes[start], at - 1 - start);
    };
    for (;;) {
        if (at >= n) bad(n < file_size ? "its header is larger than 1 MiB" : "the header has no end");
        if (bytes[at] == 0) break;  // the header's end
        const std::string name = cstring(), type = cstring();
        if (at + 4 > n) bad("header attribute '" + name + "' runs past the file");
        int32_t size;
        std::memcpy(&size, &bytes[at], 4);
        at += 4;
        if (size < 0 || static_cast<size_t>(size) > file_size - at) bad("header attribute '" + name + "' runs past the file");
        if (name == "dataWindow" && type == "box2i" && size == 16 && at + 16 <= n) {
            int32_t box[4];
            std::memcpy(box, &bytes[at], 16);
            const int64_t w = int64_t(box[2]) - box[0] + 1, h = int64_t(box[3]) - box[1] + 1;
            if (w <= 0 || h <= 0 || w > (int64_t(1) << 20) || h > static_cast<int64_t>(file_size / 8))
                bad("its data window (" + std::to_string(w) + " x " + std::to_string(h) + ") cannot be in a file of " +
                    std::to_string(file_size) + " bytes");
        }
        at += static_cast<size_t>(size);
    }
}

}  // namespace

ExrHeaderInfo read_exr_header(const std::string& path) {
    check_header_fits_file(path);
    try {
        Imf::InputFile in(path.c_str());
        const Imf::Header& header = in.header();
        ExrHeaderInfo info;
        const Imath::Box2i d = header.dataWindow(), v = header.displayWindow();
        info.data_x0 = d.min.x, info.data_y0 = d.min.y, info.data_x1 = d.max.x, info.data_y1 = d.max.y;
        info.display_x0 = v.min.x, info.display_y0 = v.min.y, info.display_x1 = v.max.x, info.display_y1 = v.max.y;
        for (auto c = header.channels().begin(); c != header.channels().end(); ++c)
            info.channels[c.name()] = c.channel().type == Imf::HALF    ? "half"
                                      : c.channel().type == Imf::FLOAT ? "float"
                                                                        : "uint";
        for (auto it = header.begin(); it != header.end(); ++it)
            if (auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) info.metadata[it.name()] = s->value();
        info.tiled = header.hasTileDescription();
        return info;
    } catch (const std::exception& e) {
        fail("cannot read EXR", path, e);
    }
}

}  // namespace sl
