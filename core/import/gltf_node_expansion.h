#pragma once
// What a glTF node graph expands to before it is walked: a node reached by two paths places
// its mesh twice, so a graph whose paths double at each level is small as a file and
// astronomical once placed. Counted once per node (memoised, saturating), so the count itself
// costs one visit of each node and mesh.
#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace sl {

struct NodeExpansion {
    uint64_t visits = 0;     // node placements
    uint64_t triangles = 0;  // triangles placed (degenerate ones included: an upper bound)
    uint64_t vertices = 0;   // vertices placed
};

// The expansion of the graph below `roots`. Returns an empty string, or why the graph cannot
// be walked: a node that does not exist, a cycle, a hierarchy deeper than `max_depth`.
std::string count_expansion(const tinygltf::Model& model, const std::vector<int>& roots, int max_depth,
                            NodeExpansion& out);

}  // namespace sl
