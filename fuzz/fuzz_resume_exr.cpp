// libFuzzer target: any bytes as an EXR frame that --resume finds in --exr-dir. Whatever the
// file holds, the verified reader returns exactly width*height*3 finite values >= 0 or throws
// (InputError for another render's fingerprint, RuntimeFailure otherwise); never a crash or a
// read outside its buffer. With FUZZ_SEED_DIR set, a valid frame is written there first, as a
// seed for the corpus.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "foundation/errors.h"
#include "fuzz/fuzz_input_file.h"
#include "stages/output/exr_frame_check.h"
#include "stages/output/exr_io.h"

namespace {

constexpr int kW = 8, kH = 6;

sl::ExrExpectation expectation() {
    sl::ExrExpectation e;
    e.width = kW;
    e.height = kH;
    e.fingerprint_key = "slowlight:settings";
    e.fingerprint = "00000000fuzzfuzz";
    e.frame = 3;
    return e;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    if (const char* dir = std::getenv("FUZZ_SEED_DIR")) {
        std::vector<float> rgb(kW * kH * 3);
        for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.01f * static_cast<float>(i);
        const sl::ExrExpectation e = expectation();
        std::map<std::string, std::string> meta = {{e.fingerprint_key, e.fingerprint},
                                                   {sl::kFrameIndexKey, "3"},
                                                   {sl::kChecksumKey, sl::pixel_checksum(rgb.data(), rgb.size())}};
        sl::write_exr(std::string(dir) + "/frame_0003.exr", kW, kH, rgb.data(), meta);
    }
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = sl::fuzz::write_scratch(data, size, ".exr");
    try {
        std::vector<float> rgb = sl::read_verified_exr(path, expectation());
        if (rgb.size() != size_t(kW) * kH * 3) __builtin_trap();
        for (float v : rgb)
            if (!(v >= 0) || !std::isfinite(v)) __builtin_trap();
    } catch (const sl::InputError&) {
    } catch (const sl::RuntimeFailure&) {
    }
    return 0;
}
