#include "stages/output/exr_frame_check.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

#include "config/input_file.h"
#include "foundation/xxh64.h"
#include "foundation/errors.h"
#include "stages/output/exr_header_scan.h"
#include "stages/output/exr_io.h"

namespace sl {

namespace {

std::string hex16(uint64_t h) {
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
    return hex;
}

}  // namespace

std::string pixel_checksum(const float* values, size_t count) {
    Xxh64 sum;
    sum.update(values, count * sizeof(float));
    return hex16(sum.value());
}

std::vector<float> read_verified_exr(const std::string& path, const ExrExpectation& e) {
    auto bad = [&](const std::string& why) { return RuntimeFailure("--resume: " + path + ": " + why); };
    const uint64_t pixels = static_cast<uint64_t>(e.width) * static_cast<uint64_t>(e.height);
    // Float RGB at most, plus room for the header and the offset table: anything larger is not ours.
    const uint64_t max_bytes = pixels * 12 + uint64_t(e.height) * 8 + (uint64_t(1) << 20);
    try {
        check_input_file(path, max_bytes, "--resume: " + path, "frame written by this render");
    } catch (const InputError& err) {
        throw RuntimeFailure(err.what());
    }
    const ExrHeaderInfo h = scan_exr_header(path, "--resume: " + path);  // without OpenEXR: nothing sized from the file yet

    // Before the fingerprint: an older build's frame would otherwise be called another render's.
    if (!h.metadata.count(kChecksumKey))
        for (const char* older : kOlderChecksumKeys)
            if (h.metadata.count(older))
                throw InputError("--resume: " + path + ": written by an older slowlight (its pixels' checksum is " +
                                 older + ", this one verifies " + kChecksumKey +
                                 "); use another --exr-dir or remove its frames");

    auto fp = h.metadata.find(e.fingerprint_key);
    if (fp == h.metadata.end() || fp->second != e.fingerprint)
        throw InputError("--resume: " + path + " was rendered from a different scene or settings (fingerprint " +
                         (fp == h.metadata.end() ? std::string("missing") : fp->second) + ", this render " +
                         e.fingerprint + "); use another --exr-dir or remove it");

    require_exr_size(path, h, {e.width, e.height}, "--resume: " + path);
    const std::map<std::string, std::string> rgb = {{"B", "float"}, {"G", "float"}, {"R", "float"}};
    if (h.channels != rgb) {
        std::string got;
        for (const auto& [name, type] : h.channels) got += (got.empty() ? "" : ", ") + name + " " + type;
        throw bad("has channels [" + got + "], not float R, G, B");
    }
    auto index = h.metadata.find(kFrameIndexKey);
    const std::string index_text = index == h.metadata.end() ? "none" : index->second;
    const std::string want_index = e.frame ? std::to_string(*e.frame) : "none";
    if (index_text != want_index)
        throw bad("carries frame index " + index_text + ", not " + want_index + " (a frame copied onto another's name?)");
    auto sum = h.metadata.find(kChecksumKey);
    if (sum == h.metadata.end()) throw bad("has no pixel checksum");

    ExrImage img = read_exr(path, {e.width, e.height});
    if (img.width != e.width || img.height != e.height || img.rgb.size() != pixels * 3)
        throw bad("changed while being read");
    for (size_t i = 0; i < img.rgb.size(); ++i)
        if (!(img.rgb[i] >= 0 && img.rgb[i] <= std::numeric_limits<float>::max()))
            throw bad("pixel (" + std::to_string(i / 3 % e.width) + ", " + std::to_string(i / 3 / e.width) +
                      ") holds " + std::to_string(img.rgb[i]) + ", not a finite radiance >= 0");
    if (pixel_checksum(img.rgb.data(), img.rgb.size()) != sum->second)
        throw bad("its pixels do not match the checksum written with them (edited or damaged)");
    return std::move(img.rgb);
}

}  // namespace sl
