#pragma once
/// \file GltfTangents_p.h
/// Private to the glTF loader: per-vertex tangents for normal maps when a primitive has none.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <vector>

namespace mvcl::gltf {

/// Tangents from the uv parametrisation (Lengyel's method: each triangle's ∂p/∂u and ∂p/∂v,
/// summed per vertex, made perpendicular to the vertex normal; w = handedness). `normals` may be
/// empty (face normals are used then). Vertices without a usable uv gradient get any tangent
/// perpendicular to their normal.
std::vector<glm::vec4> generateTangents(const std::vector<glm::vec3> &positions,
                                        const std::vector<glm::vec3> &normals, const std::vector<glm::vec2> &uvs,
                                        const std::vector<glm::uvec3> &triangles);

} // namespace mvcl::gltf
