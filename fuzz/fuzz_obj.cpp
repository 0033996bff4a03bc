// libFuzzer target: any bytes as the OBJ file of a mesh shape. A malformed mesh must end in an
// InputError naming the file, never a crash, a hang, or an index outside its vertices.
#include <cstddef>
#include <cstdint>

#include "core/errors.h"
#include "core/mesh_loader.h"
#include "fuzz/fuzz_input_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    sl::ShapeDesc shape;
    shape.type = sl::ShapeType::Mesh;
    shape.file = sl::fuzz::write_scratch(data, size, ".obj");
    try {
        sl::TriangleSoup soup = sl::load_obj_mesh(shape, "fuzz.json");
        for (uint32_t i : soup.indices)
            if (i >= soup.vertices.size()) __builtin_trap();  // an index the renderer would follow out of bounds
    } catch (const sl::InputError&) {
    }
    return 0;
}
