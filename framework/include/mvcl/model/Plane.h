#pragma once
/// \file Plane.h
/// An infinite plane {p : dot(normal, p) = offset}. Planes are not in the BVH (they are unbounded);
/// the tracer tests them after traversal.

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>

namespace mvcl {

struct Plane {
    std::string name;
    glm::vec3 normal{0.f, 1.f, 0.f}; ///< unit
    float offset = 0.f;
    uint32_t material = 0;
    int layer = 0;
};

} // namespace mvcl
