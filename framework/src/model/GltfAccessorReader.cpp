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

std::vector<float> GltfAccessorReader::readFloats(int accessor, int components) const {
    const AccessorLayout &l = m_validator.layout(accessor);
    const std::size_t n = std::size_t(components);
    std::vector<float> out(std::size_t(l.count) * n, 0.f);
    const auto decode = [&](const unsigned char *p, float *v) {
        for (int c = 0; c < components; ++c)
            v[c] = readComponent(p + std::size_t(c * l.componentSize), l.componentType, l.normalized);
    };
    if (l.data)
        for (std::size_t i = 0; i < std::size_t(l.count); ++i) decode(l.data + i * l.stride, out.data() + i * n);
    for (std::uint64_t k = 0; k < l.sparseCount; ++k) {
        const std::uint32_t target =
            readUnsignedInteger(l.sparseIndices + k * std::uint64_t(indexSize(l.sparseIndexType)), l.sparseIndexType);
        decode(l.sparseValues + k * l.elemSize, out.data() + std::size_t(target) * n); // target < count: validated
    }
    return out;
}

std::vector<glm::vec2> GltfAccessorReader::readVec2(int accessor) const {
    const std::vector<float> f = readFloats(accessor, 2);
    std::vector<glm::vec2> out(f.size() / 2);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::vec2(f[2 * i], f[2 * i + 1]);
    return out;
}

std::vector<glm::vec3> GltfAccessorReader::readVec3(int accessor) const {
    const std::vector<float> f = readFloats(accessor, 3);
    std::vector<glm::vec3> out(f.size() / 3);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::vec3(f[3 * i], f[3 * i + 1], f[3 * i + 2]);
    return out;
}

std::vector<glm::vec4> GltfAccessorReader::readVec4(int accessor) const {
    const std::vector<float> f = readFloats(accessor, 4);
    std::vector<glm::vec4> out(f.size() / 4);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::vec4(f[4 * i], f[4 * i + 1], f[4 * i + 2], f[4 * i + 3]);
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
