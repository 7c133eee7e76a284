#include "GltfValidator_p.h"

#include <cmath>
#include <cstring>
#include <set>

namespace mvcl::gltf {

namespace {

// Overflow-checked uint64 arithmetic: hostile files put byteOffsets near 2^64 and counts near
// 2^31 precisely so that a naive `offset + stride * count` wraps around and passes the check.
bool checkedMul(std::uint64_t a, std::uint64_t b, std::uint64_t &out) {
    return !__builtin_mul_overflow(a, b, &out);
}
bool checkedAdd(std::uint64_t a, std::uint64_t b, std::uint64_t &out) {
    return !__builtin_add_overflow(a, b, &out);
}

bool allFinite(const std::vector<double> &v) {
    for (double x : v)
        if (!std::isfinite(x)) return false;
    return true;
}

/// Extensions we either implement or can ignore without changing the geometry we load.
/// Anything else in `extensionsRequired` (Draco, meshopt, ...) means we would load garbage.
const std::set<std::string> &supportedRequiredExtensions() {
    static const std::set<std::string> kSupported = {
        "KHR_lights_punctual",        // lights are read
        "KHR_materials_transmission", // mapped to transparency
        "KHR_materials_ior",          // mapped to ior
        "KHR_mesh_quantization",      // integer positions/normals are decoded generically
        "KHR_texture_transform",      // applied to texture coordinates
        "KHR_materials_emissive_strength", // scales emission
    };
    return kSupported;
}


} // namespace

bool GltfValidator::isSupportedRequiredExtension(const std::string &name) {
    return supportedRequiredExtensions().count(name) != 0;
}

std::uint32_t readUnsignedInteger(const unsigned char *p, int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v;
        std::memcpy(&v, p, 2);
        return v;
    }
    default: {
        std::uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
    }
}

GltfValidator::GltfValidator(GltfContext &context) : m_context(context), m_model(context.model()) {}

int GltfValidator::componentSize(int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0; // INT and DOUBLE are not glTF 2.0 component types
    }
}

int GltfValidator::componentCount(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
    }
}

std::string GltfValidator::describeAccessor(int accessor) const {
    std::string s = "accessor " + std::to_string(accessor);
    if (accessor >= 0 && std::size_t(accessor) < m_accessorUse.size() &&
        !m_accessorUse[std::size_t(accessor)].empty())
        s += " (" + m_accessorUse[std::size_t(accessor)] + ")";
    return s;
}

void GltfValidator::validate() {
    validateAsset();
    validateExtensions();
    validateBufferViews();
    noteAccessorUses();
    validateAccessors();
    validateMeshes();
    validateNodes();
    resolveScene();
}

void GltfValidator::validateAsset() {
    // tinygltf only checks that asset.version exists; "" or "1.0" would be read as if 2.0.
    const std::string &version = m_model.asset.version;
    if (version.size() < 3 || version.compare(0, 2, "2.") != 0)
        m_context.fail("asset.version is '" + version + "', expected a glTF 2.x version such as \"2.0\"");
    const std::string &minVersion = m_model.asset.minVersion;
    if (!minVersion.empty() && minVersion != "2.0")
        m_context.fail("asset.minVersion '" + minVersion + "' is newer than the glTF 2.0 we read");
}

void GltfValidator::validateExtensions() {
    for (const std::string &ext : m_model.extensionsRequired)
        if (!supportedRequiredExtensions().count(ext))
            m_context.fail("the file requires extension " + ext + ", which mvcl does not support");
}

void GltfValidator::validateBufferViews() {
    const auto &views = m_model.bufferViews;
    for (std::size_t i = 0; i < views.size(); ++i) {
        const tinygltf::BufferView &bv = views[i];
        const std::string name = "bufferView " + std::to_string(i);
        if (bv.buffer < 0 || std::size_t(bv.buffer) >= m_model.buffers.size())
            m_context.fail(name + " refers to buffer " + std::to_string(bv.buffer) + ", but the file has " +
                           std::to_string(m_model.buffers.size()) + " buffers");
        if (bv.byteLength < 1) m_context.fail(name + " has byteLength 0");
        if (bv.byteStride != 0 && (bv.byteStride < 4 || bv.byteStride > 252 || bv.byteStride % 4 != 0))
            m_context.fail(name + " has byteStride " + std::to_string(bv.byteStride) +
                           " (must be a multiple of 4 in [4, 252])");
        const std::uint64_t bufferSize = m_model.buffers[std::size_t(bv.buffer)].data.size();
        std::uint64_t end = 0;
        if (!checkedAdd(bv.byteOffset, bv.byteLength, end))
            m_context.fail(name + ": byteOffset + byteLength overflows 64 bits");
        if (end > bufferSize)
            m_context.fail(name + " ends at byte " + std::to_string(end) + ", " +
                           std::to_string(end - bufferSize) + " bytes past the end of buffer " +
                           std::to_string(bv.buffer) + " (" + std::to_string(bufferSize) + " bytes)");
    }
}

void GltfValidator::noteAccessorUses() {
    m_accessorUse.assign(m_model.accessors.size(), std::string());
    const auto note = [&](int accessor, const std::string &use) {
        if (accessor >= 0 && std::size_t(accessor) < m_accessorUse.size() &&
            m_accessorUse[std::size_t(accessor)].empty())
            m_accessorUse[std::size_t(accessor)] = use;
    };
    for (std::size_t m = 0; m < m_model.meshes.size(); ++m) {
        const std::string mesh = m_context.describeMesh(int(m));
        for (const tinygltf::Primitive &prim : m_model.meshes[m].primitives) {
            note(prim.indices, "indices of " + mesh);
            for (const auto &[semantic, accessor] : prim.attributes) note(accessor, semantic + " of " + mesh);
        }
    }
}

void GltfValidator::validateAccessors() {
    const auto &accessors = m_model.accessors;
    m_layouts.assign(accessors.size(), AccessorLayout{});
    for (std::size_t i = 0; i < accessors.size(); ++i) {
        const tinygltf::Accessor &acc = accessors[i];
        const std::string name = describeAccessor(int(i));
        AccessorLayout &layout = m_layouts[i];
        layout.componentType = acc.componentType;
        layout.componentSize = componentSize(acc.componentType);
        layout.components = componentCount(acc.type);
        layout.normalized = acc.normalized;
        layout.count = acc.count;
        if (layout.componentSize == 0)
            m_context.fail(name + " has componentType " + std::to_string(acc.componentType) +
                           ", which glTF 2.0 does not allow");
        if (layout.components == 0) m_context.fail(name + " has an unknown type");
        if (acc.count == 0) m_context.fail(name + " has count 0 (glTF requires at least 1 element)");

        // Matrix columns of 1- and 2-byte components are padded to 4-byte boundaries.
        std::uint64_t elemSize = std::uint64_t(layout.components) * std::uint64_t(layout.componentSize);
        if (acc.type == TINYGLTF_TYPE_MAT2 && layout.componentSize == 1) elemSize = 8;
        if (acc.type == TINYGLTF_TYPE_MAT3 && layout.componentSize == 1) elemSize = 12;
        if (acc.type == TINYGLTF_TYPE_MAT3 && layout.componentSize == 2) elemSize = 24;
        layout.elemSize = elemSize;

        if (acc.bufferView >= 0) {
            if (std::size_t(acc.bufferView) >= m_model.bufferViews.size())
                m_context.fail(name + " refers to bufferView " + std::to_string(acc.bufferView) +
                               ", but the file has " + std::to_string(m_model.bufferViews.size()));
            const tinygltf::BufferView &bv = m_model.bufferViews[std::size_t(acc.bufferView)];
            if (bv.byteStride != 0 && bv.byteStride < elemSize)
                m_context.fail(name + ": bufferView " + std::to_string(acc.bufferView) + " byteStride " +
                               std::to_string(bv.byteStride) + " is smaller than the element size " +
                               std::to_string(elemSize));
            layout.stride = bv.byteStride != 0 ? bv.byteStride : elemSize;
            // glTF: byteOffset + stride·(count − 1) + elemSize ≤ bufferView.byteLength
            std::uint64_t span = 0, end = 0;
            if (!checkedMul(layout.stride, acc.count - 1, span) || !checkedAdd(span, elemSize, span) ||
                !checkedAdd(span, acc.byteOffset, end))
                m_context.fail(name + ": byteOffset " + std::to_string(acc.byteOffset) + " + " +
                               std::to_string(acc.count) + " elements overflows 64 bits (bufferView " +
                               std::to_string(acc.bufferView) + ")");
            if (end > bv.byteLength)
                m_context.fail(name + " reads " + std::to_string(end - bv.byteLength) +
                               " bytes past the end of bufferView " + std::to_string(acc.bufferView) +
                               " (needs " + std::to_string(end) + ", has " + std::to_string(bv.byteLength) +
                               ")");
            layout.data = m_model.buffers[std::size_t(bv.buffer)].data.data() + bv.byteOffset + acc.byteOffset;
        } else {
            // No bufferView: all zeros (plus sparse values). Still bounded, so that a tiny file
            // cannot make us allocate gigabytes of zeros.
            std::uint64_t bytes = 0;
            if (!checkedMul(elemSize, acc.count, bytes) || bytes > (std::uint64_t(1) << 30))
                m_context.fail(name + " has no bufferView and " + std::to_string(acc.count) +
                               " elements, more than mvcl accepts for zero-filled data");
            layout.stride = elemSize;
        }
        if (acc.sparse.isSparse) validateSparse(int(i), layout);
    }
}

void GltfValidator::validateSparse(int index, AccessorLayout &layout) {
    const tinygltf::Accessor &acc = m_model.accessors[std::size_t(index)];
    const std::string name = describeAccessor(index) + " (sparse)";
    const auto &sp = acc.sparse;
    if (sp.count < 1 || std::uint64_t(sp.count) > acc.count)
        m_context.fail(name + ": sparse count " + std::to_string(sp.count) + " is not in [1, " +
                       std::to_string(acc.count) + "]");
    const int indexSize = sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                          : sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                          : sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                                                : 0;
    if (indexSize == 0)
        m_context.fail(name + ": sparse indices componentType " + std::to_string(sp.indices.componentType) +
                       " is not an unsigned integer type");
    const auto region = [&](int view, int offset, std::uint64_t bytes, const char *what) {
        if (view < 0 || std::size_t(view) >= m_model.bufferViews.size())
            m_context.fail(name + ": sparse " + what + " bufferView " + std::to_string(view) + " does not exist");
        if (offset < 0) m_context.fail(name + ": sparse " + what + " byteOffset is negative");
        const tinygltf::BufferView &bv = m_model.bufferViews[std::size_t(view)];
        std::uint64_t end = 0;
        if (!checkedAdd(std::uint64_t(offset), bytes, end) || end > bv.byteLength)
            m_context.fail(name + ": sparse " + what + " read past the end of bufferView " + std::to_string(view));
        return m_model.buffers[std::size_t(bv.buffer)].data.data() + bv.byteOffset + std::uint64_t(offset);
    };
    std::uint64_t valueBytes = 0;
    if (!checkedMul(std::uint64_t(sp.count), layout.elemSize, valueBytes))
        m_context.fail(name + ": sparse values size overflows");
    layout.sparseCount = std::uint64_t(sp.count);
    layout.sparseIndexType = sp.indices.componentType;
    layout.sparseIndices = region(sp.indices.bufferView, sp.indices.byteOffset,
                                  std::uint64_t(sp.count) * std::uint64_t(indexSize), "indices");
    layout.sparseValues = region(sp.values.bufferView, sp.values.byteOffset, valueBytes, "values");
    // The spec requires strictly increasing indices; that also makes every index distinct.
    std::uint64_t previous = 0;
    for (std::uint64_t k = 0; k < layout.sparseCount; ++k) {
        const std::uint64_t target = readUnsignedInteger(layout.sparseIndices + k * std::uint64_t(indexSize),
                                                  layout.sparseIndexType);
        if (target >= acc.count)
            m_context.fail(name + ": sparse index " + std::to_string(target) + " is not below count " +
                           std::to_string(acc.count));
        if (k > 0 && target <= previous)
            m_context.fail(name + ": sparse indices are not strictly increasing");
        previous = target;
    }
}

void GltfValidator::validateMeshes() {
    const std::size_t accessorCount = m_model.accessors.size();
    for (std::size_t m = 0; m < m_model.meshes.size(); ++m) {
        const std::string mesh = m_context.describeMesh(int(m));
        const auto &prims = m_model.meshes[m].primitives;
        // tinygltf silently reads a non-array "primitives" as none; glTF requires at least one.
        if (prims.empty()) m_context.fail(mesh + " has no primitives (glTF requires at least one)");
        for (std::size_t p = 0; p < prims.size(); ++p) {
            const tinygltf::Primitive &prim = prims[p];
            const std::string where = mesh + " primitive " + std::to_string(p);
            if (prim.mode < TINYGLTF_MODE_POINTS || prim.mode > TINYGLTF_MODE_TRIANGLE_FAN)
                m_context.fail(where + " has unknown mode " + std::to_string(prim.mode));
            if (prim.material < -1 || (prim.material >= 0 && std::size_t(prim.material) >= m_model.materials.size()))
                m_context.fail(where + " refers to material " + std::to_string(prim.material) +
                               ", but the file has " + std::to_string(m_model.materials.size()));
            if (prim.indices < -1 || (prim.indices >= 0 && std::size_t(prim.indices) >= accessorCount))
                m_context.fail(where + " refers to indices accessor " + std::to_string(prim.indices) +
                               ", but the file has " + std::to_string(accessorCount));
            if (prim.indices >= 0) {
                const tinygltf::Accessor &acc = m_model.accessors[std::size_t(prim.indices)];
                const bool unsignedInt = acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                         acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                                         acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
                if (acc.type != TINYGLTF_TYPE_SCALAR || !unsignedInt || acc.normalized)
                    m_context.fail(describeAccessor(prim.indices) +
                                   " is used as indices but is not an unsigned integer SCALAR accessor");
            }
            std::uint64_t vertexCount = 0;
            bool first = true;
            for (const auto &[semantic, accessor] : prim.attributes) {
                if (accessor < 0 || std::size_t(accessor) >= accessorCount)
                    m_context.fail(where + " attribute " + semantic + " refers to accessor " +
                                   std::to_string(accessor) + ", but the file has " + std::to_string(accessorCount));
                const tinygltf::Accessor &acc = m_model.accessors[std::size_t(accessor)];
                if ((semantic == "POSITION" || semantic == "NORMAL") && acc.type != TINYGLTF_TYPE_VEC3)
                    m_context.fail(describeAccessor(accessor) + " must be VEC3");
                if (first) vertexCount = acc.count;
                else if (acc.count != vertexCount)
                    m_context.fail(where + ": attribute " + semantic + " has " + std::to_string(acc.count) +
                                   " elements, other attributes have " + std::to_string(vertexCount));
                first = false;
            }
        }
    }
}

void GltfValidator::validateNodes() {
    const std::size_t n = m_model.nodes.size();
    m_parents.assign(n, -1);
    for (std::size_t i = 0; i < n; ++i) {
        const tinygltf::Node &node = m_model.nodes[i];
        const std::string name = m_context.describeNode(int(i));
        if (node.mesh < -1 || (node.mesh >= 0 && std::size_t(node.mesh) >= m_model.meshes.size()))
            m_context.fail(name + " refers to mesh " + std::to_string(node.mesh) + ", but the file has " +
                           std::to_string(m_model.meshes.size()));
        if (node.camera < -1 || (node.camera >= 0 && std::size_t(node.camera) >= m_model.cameras.size()))
            m_context.fail(name + " refers to camera " + std::to_string(node.camera) + ", but the file has " +
                           std::to_string(m_model.cameras.size()));
        const auto checkVector = [&](const std::vector<double> &v, std::size_t size, const char *what) {
            if (!v.empty() && v.size() != size)
                m_context.fail(name + " " + what + " has " + std::to_string(v.size()) + " numbers, expected " +
                               std::to_string(size));
            if (!allFinite(v)) m_context.fail(name + " " + what + " contains a non-finite number");
        };
        checkVector(node.matrix, 16, "matrix");
        // Column-major: elements 3, 7, 11, 15 are the bottom row. Anything but (0, 0, 0, 1) is a
        // projective matrix, which no translation·rotation·scale can express (glTF §3.5.3).
        if (node.matrix.size() == 16 &&
            (node.matrix[3] != 0.0 || node.matrix[7] != 0.0 || node.matrix[11] != 0.0 || node.matrix[15] != 1.0))
            m_context.fail(name + " matrix has bottom row (" + std::to_string(node.matrix[3]) + ", " +
                           std::to_string(node.matrix[7]) + ", " + std::to_string(node.matrix[11]) + ", " +
                           std::to_string(node.matrix[15]) +
                           "), not (0, 0, 0, 1); glTF node matrices must decompose into translation, rotation "
                           "and scale");
        checkVector(node.translation, 3, "translation");
        checkVector(node.rotation, 4, "rotation");
        checkVector(node.scale, 3, "scale");
        const auto light = node.extensions.find("KHR_lights_punctual");
        if (light != node.extensions.end()) {
            const tinygltf::Value &index = light->second.Get("light");
            if (!index.IsInt() || index.GetNumberAsInt() < 0 ||
                std::size_t(index.GetNumberAsInt()) >= m_model.lights.size())
                m_context.fail(name + " refers to a KHR_lights_punctual light that does not exist");
        }
        for (int child : node.children) {
            if (child < 0 || std::size_t(child) >= n)
                m_context.fail(name + " has child " + std::to_string(child) + ", but the file has " +
                               std::to_string(n) + " nodes");
            int &parent = m_parents[std::size_t(child)];
            if (parent == int(i))
                m_context.fail(m_context.describeNode(child) + " is listed twice as a child of " + name);
            if (parent != -1)
                m_context.fail(m_context.describeNode(child) + " has two parents (" +
                               m_context.describeNode(parent) + " and " + name + "); glTF nodes form a forest");
            parent = int(i);
        }
    }
    // With at most one parent per node, a cycle is a loop of parent links. Walk up from each node
    // once (iteratively: a 10^5-deep chain must not touch the call stack), colouring as we go.
    enum : unsigned char { Unvisited, OnPath, Done };
    std::vector<unsigned char> state(n, Unvisited);
    std::vector<int> path;
    for (std::size_t start = 0; start < n; ++start) {
        path.clear();
        int v = int(start);
        while (v != -1 && state[std::size_t(v)] == Unvisited) {
            state[std::size_t(v)] = OnPath;
            path.push_back(v);
            v = m_parents[std::size_t(v)];
        }
        if (v != -1 && state[std::size_t(v)] == OnPath)
            m_context.fail("the node hierarchy has a cycle through " + m_context.describeNode(v) +
                           " (a node is its own ancestor)");
        for (int p : path) state[std::size_t(p)] = Done;
    }
}

void GltfValidator::resolveScene() {
    const auto &scenes = m_model.scenes;
    m_rootNodes.clear();
    int sceneIndex = m_model.defaultScene;
    if (sceneIndex >= 0 && std::size_t(sceneIndex) >= scenes.size())
        m_context.fail("\"scene\" is " + std::to_string(sceneIndex) + ", but the file has " +
                       std::to_string(scenes.size()) + " scenes");
    if (sceneIndex < 0 && !scenes.empty()) sceneIndex = 0; // glTF: no "scene" → any; we take the first
    if (sceneIndex < 0) {
        // No scenes at all: show every root node rather than nothing.
        for (std::size_t i = 0; i < m_parents.size(); ++i)
            if (m_parents[i] == -1) m_rootNodes.push_back(int(i));
        return;
    }
    std::vector<bool> seen(m_model.nodes.size(), false);
    for (int node : scenes[std::size_t(sceneIndex)].nodes) {
        const std::string where = "scene " + std::to_string(sceneIndex);
        if (node < 0 || std::size_t(node) >= m_model.nodes.size())
            m_context.fail(where + " lists node " + std::to_string(node) + ", but the file has " +
                           std::to_string(m_model.nodes.size()) + " nodes");
        if (m_parents[std::size_t(node)] != -1)
            m_context.fail(where + " lists " + m_context.describeNode(node) + " as a root, but it is a child of " +
                           m_context.describeNode(m_parents[std::size_t(node)]));
        if (seen[std::size_t(node)]) m_context.fail(where + " lists " + m_context.describeNode(node) + " twice");
        seen[std::size_t(node)] = true;
        m_rootNodes.push_back(node);
    }
}

} // namespace mvcl::gltf
