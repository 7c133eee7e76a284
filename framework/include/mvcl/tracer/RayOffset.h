#pragma once
/// \file RayOffset.h
/// Spawned-ray origins offset by the hit point's error bound (pbrt-v4 OffsetRayOrigin): far enough
/// to never re-hit the surface, close enough to not skip a layer a hair away. No fixed epsilon.

#include <mvcl/core/FloatBits.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>

namespace mvcl {

/// The move offsetRayOrigin() makes toward the side the geometric normal n faces: the error
/// bound projected onto n, along n. A point that spawns several rays finds it once.
inline glm::vec3 originOffsetAlong(const glm::vec3 &pError, const glm::vec3 &n) {
    // Products rounded on their own (mulUnfused): the origin must not depend on FMA contraction.
    const float d = mulUnfused(std::abs(n.x), pError.x) + mulUnfused(std::abs(n.y), pError.y) +
                    mulUnfused(std::abs(n.z), pError.z);
    return d * n;
}

/// True if offsetRayOrigin() moves a ray toward `w` to the side n does not face (w·n < 0).
inline bool leavesBehind(const glm::vec3 &n, const glm::vec3 &w) {
    return mulUnfused(w.x, n.x) + mulUnfused(w.y, n.y) + mulUnfused(w.z, n.z) < 0.f;
}

/// p + offset, then one float step further in each component the offset moves: the origin
/// offsetRayOrigin() gives on the side `offset` points to (±originOffsetAlong()).
inline glm::vec3 offsetPoint(const glm::vec3 &p, const glm::vec3 &offset) {
    glm::vec3 po = p + offset;
    for (int i = 0; i < 3; ++i) {
        if (offset[i] > 0.f) po[i] = nextFloatUp(po[i]);
        else if (offset[i] < 0.f) po[i] = nextFloatDown(po[i]);
    }
    return po;
}

/// Moves p off the surface with geometric normal n, to the side `w` points to.
inline glm::vec3 offsetRayOrigin(const glm::vec3 &p, const glm::vec3 &pError, const glm::vec3 &n,
                                 const glm::vec3 &w) {
    const glm::vec3 offset = originOffsetAlong(pError, n);
    return offsetPoint(p, leavesBehind(n, w) ? -offset : offset);
}

} // namespace mvcl
