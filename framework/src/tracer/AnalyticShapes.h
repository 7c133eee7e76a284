#pragma once
// Private: sphere and plane intersection in double precision. Spheres and planes are few, so
// double costs nothing measurable and makes t accurate to float rounding (spawned rays offset by
// the error bounds in interaction() then never re-hit the surface).

#include "KernelIsa.h"

#include <glm/vec3.hpp>

#include <cmath>
#include <utility>

namespace mvcl::detail {
inline namespace MVCL_ISA_NAMESPACE { // one copy per kernel instruction set (KernelIsa.h)

/// Roots of |o + t·d − c|² = r², ascending, in the numerically careful form of Ray Tracing Gems
/// ch. 7 (Haines et al.): the discriminant from the perpendicular distance, q with the sign of b
/// to avoid cancellation. Returns the number of roots (0 or 2).
inline int sphereRoots(const glm::vec3 &origin, const glm::vec3 &direction,
                       const glm::vec3 &center, float radius, double roots[2]) {
    const double fx = double(origin.x) - double(center.x);
    const double fy = double(origin.y) - double(center.y);
    const double fz = double(origin.z) - double(center.z);
    const double dx = direction.x, dy = direction.y, dz = direction.z;
    const double a = dx * dx + dy * dy + dz * dz;
    const double b = fx * dx + fy * dy + fz * dz; // half of the usual b
    const double r = radius;
    const double c = (fx * fx + fy * fy + fz * fz) - r * r;
    const double s = b / a;
    const double lx = fx - s * dx, ly = fy - s * dy, lz = fz - s * dz;
    const double disc = r * r - (lx * lx + ly * ly + lz * lz);
    if (!(disc >= 0.0)) return 0;
    const double q = -(b + std::copysign(std::sqrt(a * disc), b));
    if (q == 0.0) return 0; // origin on the sphere, ray tangent: nothing in front
    double t0 = c / q, t1 = q / a;
    if (t0 > t1) std::swap(t0, t1);
    roots[0] = t0;
    roots[1] = t1;
    return 2;
}

/// t of the plane dot(n, p) = offset, or NaN when the ray is parallel to it.
inline double planeT(const glm::vec3 &origin, const glm::vec3 &direction, const glm::vec3 &normal,
                     float offset) {
    const double denom = double(normal.x) * direction.x + double(normal.y) * direction.y +
                         double(normal.z) * direction.z;
    if (denom == 0.0) return std::nan("");
    const double num = double(offset) - (double(normal.x) * origin.x + double(normal.y) * origin.y +
                                         double(normal.z) * origin.z);
    return num / denom;
}

} // namespace MVCL_ISA_NAMESPACE
} // namespace mvcl::detail
