#pragma once
/// \file GltfAccessorReader_p.h
/// Private to the glTF loader: decodes accessors whose bounds GltfValidator has already checked.

#include "GltfValidator_p.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace mvcl::gltf {

class GltfAccessorReader {
public:
    explicit GltfAccessorReader(const GltfValidator &validator) : m_validator(validator) {}

    /// A VEC3 accessor as floats (integer types converted per the glTF rules, normalised or not),
    /// with sparse substitution applied.
    std::vector<glm::vec3> readVec3(int accessor) const;
    /// The same for VEC2 (texture coordinates) and VEC4 (tangents) accessors.
    std::vector<glm::vec2> readVec2(int accessor) const;
    std::vector<glm::vec4> readVec4(int accessor) const;
    /// An unsigned integer SCALAR accessor (sparse applied).
    std::vector<std::uint32_t> readIndices(int accessor) const;

private:
    /// `components` floats per element; the caller has checked the accessor's type has them.
    std::vector<float> readFloats(int accessor, int components) const;

    const GltfValidator &m_validator;
};

} // namespace mvcl::gltf
