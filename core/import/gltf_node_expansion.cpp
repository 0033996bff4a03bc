#include "core/import/gltf_node_expansion.h"

#include <algorithm>

namespace sl {
namespace {

// Saturating sums: past 2^62 every figure is "too many" anyway.
constexpr uint64_t kSaturated = uint64_t(1) << 62;
uint64_t add(uint64_t a, uint64_t b) { return std::min(kSaturated, a + b); }  // both <= 2^62: no wrap

// An accessor's element count, at most its view's byte length (an element takes a byte at
// least): a forged count is left to the accessor's own check, which names it when it is read.
uint64_t accessor_count(const tinygltf::Model& m, int index) {
    if (index < 0 || static_cast<size_t>(index) >= m.accessors.size()) return 0;
    const tinygltf::Accessor& a = m.accessors[static_cast<size_t>(index)];
    if (a.bufferView < 0 || static_cast<size_t>(a.bufferView) >= m.bufferViews.size()) return 0;
    return std::min<uint64_t>(a.count, m.bufferViews[static_cast<size_t>(a.bufferView)].byteLength);
}

// One placement of a mesh: its primitives' triangles and vertices, as the accessors declare them.
NodeExpansion mesh_cost(const tinygltf::Model& m, const tinygltf::Mesh& mesh) {
    NodeExpansion c;
    for (const tinygltf::Primitive& p : mesh.primitives) {
        auto pos = p.attributes.find("POSITION");
        const uint64_t vertices = pos == p.attributes.end() ? 0 : accessor_count(m, pos->second);
        const uint64_t corners = p.indices >= 0 ? accessor_count(m, p.indices) : vertices;
        const uint64_t tris = p.mode == TINYGLTF_MODE_TRIANGLE_STRIP || p.mode == TINYGLTF_MODE_TRIANGLE_FAN
                                  ? (corners > 2 ? corners - 2 : 0)
                                  : corners / 3;
        c.triangles = add(c.triangles, tris);
        c.vertices = add(c.vertices, vertices);
    }
    return c;
}

struct Walk {
    const tinygltf::Model& model;
    int max_depth;
    std::vector<NodeExpansion> below;  // per node: itself and everything under it, once placed
    std::vector<uint8_t> state;        // 0 not seen, 1 on the current path, 2 done
    std::string error;

    const NodeExpansion* node(int n, int depth) {
        if (n < 0 || static_cast<size_t>(n) >= model.nodes.size()) {
            error = "node " + std::to_string(n) + " does not exist";
            return nullptr;
        }
        const size_t i = static_cast<size_t>(n);
        if (state[i] == 2) return &below[i];
        if (state[i] == 1) {
            error = "node " + std::to_string(n) + " is its own ancestor (a cycle)";
            return nullptr;
        }
        if (depth > max_depth) {
            error = "the node hierarchy is deeper than " + std::to_string(max_depth) + " levels";
            return nullptr;
        }
        state[i] = 1;
        const tinygltf::Node& nd = model.nodes[i];
        NodeExpansion e{1, 0, 0};
        if (nd.mesh >= 0 && static_cast<size_t>(nd.mesh) < model.meshes.size()) {
            const NodeExpansion c = mesh_cost(model, model.meshes[static_cast<size_t>(nd.mesh)]);
            e.triangles = c.triangles;
            e.vertices = c.vertices;
        }
        for (int child : nd.children) {
            const NodeExpansion* c = node(child, depth + 1);
            if (!c) return nullptr;
            e.visits = add(e.visits, c->visits);
            e.triangles = add(e.triangles, c->triangles);
            e.vertices = add(e.vertices, c->vertices);
        }
        state[i] = 2;
        below[i] = e;
        return &below[i];
    }
};

}  // namespace

std::string count_expansion(const tinygltf::Model& model, const std::vector<int>& roots, int max_depth,
                            NodeExpansion& out) {
    Walk w{model, max_depth, std::vector<NodeExpansion>(model.nodes.size()), std::vector<uint8_t>(model.nodes.size(), 0), {}};
    out = {};
    for (int r : roots) {
        const NodeExpansion* e = w.node(r, 0);
        if (!e) return w.error;
        out.visits = add(out.visits, e->visits);
        out.triangles = add(out.triangles, e->triangles);
        out.vertices = add(out.vertices, e->vertices);
    }
    return {};
}

}  // namespace sl
