#pragma once
/// \file RayOffset.h
/// Spawned-ray origins offset by the hit point's error bound (pbrt-v4 OffsetRayOrigin): far enough
/// to never re-hit the surface, close enough to not skip a layer a hair away. No fixed epsilon.

#include <mvcl/core/FloatBits.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>

namespace mvcl {

/// Moves p off the surface with geometric normal n, to the side `w` points to.
inline glm::vec3 offsetRayOrigin(const glm::vec3 &p, const glm::vec3 &pError, const glm::vec3 &n,
                                 const glm::vec3 &w) {
    // Products rounded on their own (mulUnfused): the origin must not depend on FMA contraction.
    const float d = mulUnfused(std::abs(n.x), pError.x) + mulUnfused(std::abs(n.y), pError.y) +
                    mulUnfused(std::abs(n.z), pError.z);
    glm::vec3 offset = d * n;
    if (mulUnfused(w.x, n.x) + mulUnfused(w.y, n.y) + mulUnfused(w.z, n.z) < 0.f) offset = -offset;
    glm::vec3 po = p + offset;
    for (int i = 0; i < 3; ++i) {
        if (offset[i] > 0.f) po[i] = nextFloatUp(po[i]);
        else if (offset[i] < 0.f) po[i] = nextFloatDown(po[i]);
    }
    return po;
}

} // namespace mvcl
