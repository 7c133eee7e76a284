#pragma once
// Private: a plane of the scene as the tracer tests it (outside the BVH: a plane has no box).
// One type for every kernel unit (KernelIsa.h): the single-ray kernels test the planes first.

#include <glm/vec3.hpp>

#include <cstdint>

namespace mvcl::detail {

struct PlaneRecord {
    glm::vec3 normal; ///< unit length (TracerBuild.cpp normalises it with the offset)
    float offset;
    uint32_t geometry;
    uint8_t layer;
};

} // namespace mvcl::detail
