#include "GltfAccessorReader_p.h"

#include <algorithm>
#include <cstring>

namespace mvcl::gltf {

namespace {

// All reads go through memcpy: glTF data need not be aligned for the host, and memcpy of a
// known size compiles to a plain load anyway.
float readComponent(const unsigned char *p, int componentType, bool normalized) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float v;
        std::memcpy(&v, p, 4);
        return v;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const auto v = static_cast<std::int8_t>(*p);
        return normalized ? std::max(float(v) / 127.f, -1.f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? float(*p) / 255.f : float(*p);
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        std::int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(float(v) / 32767.f, -1.f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? float(v) / 65535.f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        std::uint32_t v;
        std::memcpy(&v, p, 4);
        return normalized ? float(double(v) / 4294967295.0) : float(v);
    }
    default: return 0.f; // rejected by the validator
    }
}


int indexSize(int componentType) {
    return componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
           : componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                                                                     : 4;
}

} // namespace

std::vector<glm::vec3> GltfAccessorReader::readVec3(int accessor) const {
    const AccessorLayout &l = m_validator.layout(accessor);
    std::vector<glm::vec3> out(std::size_t(l.count), glm::vec3(0.f));
    const auto decode = [&](const unsigned char *p) {
        glm::vec3 v;
        for (int c = 0; c < 3; ++c)
            v[c] = readComponent(p + std::size_t(c * l.componentSize), l.componentType, l.normalized);
        return v;
    };
    if (l.data)
        for (std::size_t i = 0; i < out.size(); ++i) out[i] = decode(l.data + i * l.stride);
    for (std::uint64_t k = 0; k < l.sparseCount; ++k) {
        const std::uint32_t target =
            readUnsignedInteger(l.sparseIndices + k * std::uint64_t(indexSize(l.sparseIndexType)), l.sparseIndexType);
        out[target] = decode(l.sparseValues + k * l.elemSize); // target < count: validated
    }
    return out;
}

std::vector<std::uint32_t> GltfAccessorReader::readIndices(int accessor) const {
    const AccessorLayout &l = m_validator.layout(accessor);
    std::vector<std::uint32_t> out(std::size_t(l.count), 0u);
    if (l.data)
        for (std::size_t i = 0; i < out.size(); ++i) out[i] = readUnsignedInteger(l.data + i * l.stride, l.componentType);
    for (std::uint64_t k = 0; k < l.sparseCount; ++k) {
        const std::uint32_t target =
            readUnsignedInteger(l.sparseIndices + k * std::uint64_t(indexSize(l.sparseIndexType)), l.sparseIndexType);
        out[target] = readUnsignedInteger(l.sparseValues + k * l.elemSize, l.componentType);
    }
    return out;
}

} // namespace mvcl::gltf
