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
#include <vector>

#include "foundation/errors.h"
#include "stages/output/atomic_file.h"
#include "stages/output/exr_file_stream.h"
#include "stages/output/exr_header_scan.h"
#include "stages/output/exr_limits.h"

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
    limit_openexr_sizes();
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
        // OpenEXR writes into 64 KiB blocks (exr_file_stream.h); the file is closed, and every
        // byte written or the failure reported, before the rename.
        ExrFileStream file(temp);
        {
            Imf::OutputFile out(file, header);
            out.setFrameBuffer(fb);
            out.writePixels(h);
        }  // (here OpenEXR writes the table of line offsets)
        file.close();
    } catch (const std::exception& e) {
        discard_file(temp);
        fail("cannot write EXR", path, e);
    }
    commit_file(temp, path);
}

ExrImage read_exr(const std::string& path, ExrSize want) {
    require_exr_size(path, scan_exr_header(path), want);
    limit_openexr_sizes();  // OpenEXR's own size guard as well: exr_limits.h says why both
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

}  // namespace sl
