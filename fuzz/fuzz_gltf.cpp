// libFuzzer target: any bytes as a binary glTF (.glb) file, read by the importer with its
// materials and lights. A malformed file (bad chunk sizes, accessors past their buffers, indices
// out of range, unsupported required extensions) must end in an InputError naming it, never a
// crash, a hang, or an accepted mesh that breaks the renderer's assumptions.
#include <cstddef>
#include <cstdint>

#include "foundation/errors.h"
#include "core/import/imported_file.h"
#include "fuzz/fuzz_input_file.h"
#include "fuzz/imported_file_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = sl::fuzz::write_scratch(data, size, ".glb");
    try {
        sl::fuzz::check_imported(sl::read_gltf(path, true));
    } catch (const sl::InputError&) {
    }
    return 0;
}
