#pragma once
/// \file GltfValidator_p.h
/// Private to the glTF loader: the checks tinygltf does not do. Runs after tinygltf has parsed
/// the file and before anything reads buffer data, so that every later read is known in bounds.

#include "GltfContext_p.h"

#include <cstdint>
#include <string>
#include <vector>

namespace mvcl::gltf {

/// Where an accessor's elements live, after all bounds have been checked.
struct AccessorLayout {
    const unsigned char *data = nullptr; ///< first element; nullptr = all zeros (no bufferView)
    std::uint64_t stride = 0;
    std::uint64_t elemSize = 0;
    std::uint64_t count = 0;
    int components = 0;
    int componentType = 0;
    int componentSize = 0;
    bool normalized = false;
    // Sparse substitution (already checked: indices strictly increasing and < count).
    std::uint64_t sparseCount = 0;
    const unsigned char *sparseIndices = nullptr;
    int sparseIndexType = 0;
    const unsigned char *sparseValues = nullptr;
};

class GltfValidator {
public:
    explicit GltfValidator(GltfContext &context);

    /// Runs every check; throws mvcl::Error (via the context) on the first problem.
    void validate();

    /// True for extensions a file may require: those mvcl implements or can ignore.
    static bool isSupportedRequiredExtension(const std::string &name);

    const AccessorLayout &layout(int accessor) const { return m_layouts[std::size_t(accessor)]; }
    /// "accessor 3 (POSITION of mesh 'Cube')": for error messages.
    std::string describeAccessor(int accessor) const;
    /// Root nodes of the scene to instantiate (validated, distinct, parentless).
    const std::vector<int> &rootNodes() const { return m_rootNodes; }
    /// Parent of each node, -1 for roots.
    const std::vector<int> &parents() const { return m_parents; }

    static int componentSize(int componentType);
    static int componentCount(int type);

private:
    void validateAsset();
    void validateExtensions();
    void validateBufferViews();
    void noteAccessorUses();
    void validateAccessors();
    void validateSparse(int index, AccessorLayout &layout);
    void validateMeshes();
    void validateNodes();
    void resolveScene();

    GltfContext &m_context;
    const tinygltf::Model &m_model;
    std::vector<AccessorLayout> m_layouts;
    std::vector<std::string> m_accessorUse;
    std::vector<int> m_parents;
    std::vector<int> m_rootNodes;
};

/// Reads one unsigned 8-, 16- or 32-bit integer (glTF index component types) from unaligned
/// memory; the caller has checked the bounds.
std::uint32_t readUnsignedInteger(const unsigned char *p, int componentType);

} // namespace mvcl::gltf
