#include "GltfMemoryEstimate_p.h"

#include <vector>

namespace mvcl::gltf {

GltfMemoryEstimate estimateGeometryMemory(const GltfContext &context, const GltfValidator &validator) {
    const tinygltf::Model &model = context.model();
    GltfMemoryEstimate estimate;
    // The validator has proven the node graph a forest: every node is reached once.
    std::vector<int> stack(validator.rootNodes().begin(), validator.rootNodes().end());
    while (!stack.empty()) {
        const tinygltf::Node &node = model.nodes[std::size_t(stack.back())];
        stack.pop_back();
        for (int child : node.children) stack.push_back(child);
        if (node.mesh < 0) continue;
        for (const tinygltf::Primitive &primitive : model.meshes[std::size_t(node.mesh)].primitives) {
            const auto position = primitive.attributes.find("POSITION");
            if (position == primitive.attributes.end() || position->second < 0) continue;
            const double vertices = double(model.accessors[std::size_t(position->second)].count);
            const double corners =
                primitive.indices >= 0 ? double(model.accessors[std::size_t(primitive.indices)].count) : vertices;
            double triangles = 0.0;
            if (primitive.mode == TINYGLTF_MODE_TRIANGLES) triangles = corners / 3.0;
            else if (primitive.mode == TINYGLTF_MODE_TRIANGLE_STRIP || primitive.mode == TINYGLTF_MODE_TRIANGLE_FAN)
                triangles = corners > 2.0 ? corners - 2.0 : 0.0;
            else continue; // points and lines are skipped by the loader
            estimate.triangles += triangles;
            estimate.vertices += vertices;
        }
    }
    estimate.bytes = estimate.triangles * kEstimatedBytesPerTriangle + estimate.vertices * kEstimatedBytesPerVertex;
    return estimate;
}

} // namespace mvcl::gltf
