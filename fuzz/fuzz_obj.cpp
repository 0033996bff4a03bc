// libFuzzer target: any bytes as an OBJ file, read by the importer with its materials (an
// `mtllib` naming a missing library is one of the errors it must report). A malformed file must
// end in an InputError naming it, never a crash, a hang, or an accepted mesh that breaks the
// renderer's assumptions (fuzz/imported_file_checks.h).
#include <cstddef>
#include <cstdint>

#include "foundation/errors.h"
#include "core/import/imported_file.h"
#include "fuzz/fuzz_input_file.h"
#include "fuzz/imported_file_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = sl::fuzz::write_scratch(data, size, ".obj");
    for (bool materials : {false, true}) {
        try {
            sl::fuzz::check_imported(sl::read_obj_mtl(path, materials));
        } catch (const sl::InputError&) {
        }
    }
    return 0;
}
