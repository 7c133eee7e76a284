#include <mvcl/tracer/TriangleIntersection.h>

#include "WatertightTriangle.h"

#include <glm/vec3.hpp>

#include <cmath>

namespace mvcl {

bool intersectTriangle(const WatertightRay &ray, const glm::vec3 &p0, const glm::vec3 &p1,
                       const glm::vec3 &p2, float tMin, float tMax, TriangleHit &hit) {
    // Zero-area triangles never hit (pbrt-v4 does the same check). Done in double so that
    // tiny but valid triangles are not mistaken for degenerate ones by underflow.
    const glm::dvec3 e1 = glm::dvec3(p1) - glm::dvec3(p0);
    const glm::dvec3 e2 = glm::dvec3(p2) - glm::dvec3(p0);
    const glm::dvec3 n(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z,
                       e1.x * e2.y - e1.y * e2.x);
    if (n.x == 0.0 && n.y == 0.0 && n.z == 0.0) return false;
    TriangleHit h;
    if (!detail::watertightIntersect(ray, p0, p1, p2, tMax, h)) return false;
    if (!(h.t > tMin && h.t < tMax)) return false;
    hit = h;
    return true;
}

bool intersectTriangle(const Ray &ray, const glm::vec3 &p0, const glm::vec3 &p1,
                       const glm::vec3 &p2, float tMin, float tMax, TriangleHit &hit) {
    return intersectTriangle(WatertightRay(ray), p0, p1, p2, tMin, tMax, hit);
}

} // namespace mvcl
