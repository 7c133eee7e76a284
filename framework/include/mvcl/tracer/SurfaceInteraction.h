#pragma once
/// \file SurfaceInteraction.h

#include <glm/vec3.hpp>

#include <cstdint>

namespace mvcl {

/// Everything shading needs about a hit.
struct SurfaceInteraction {
    glm::vec3 position{0.f};
    /// Conservative bound on the absolute error of `position` per axis (pbrt-v4 §6.8).
    glm::vec3 positionError{0.f};
    glm::vec3 geometricNormal{0.f, 0.f, 1.f}; ///< unit, as the primitive is wound
    glm::vec3 shadingNormal{0.f, 0.f, 1.f};   ///< unit, interpolated, same side as geometricNormal
    uint32_t material = 0;
    int layer = 0;
};

} // namespace mvcl
