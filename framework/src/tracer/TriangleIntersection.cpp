#include <mvcl/tracer/TriangleIntersection.h>

#include "WatertightTriangle.h"

#include <glm/vec3.hpp>

#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mvcl {

WatertightRay::WatertightRay(const Ray &ray) : origin(ray.origin) {
    const glm::vec3 ad(std::fabs(ray.direction.x), std::fabs(ray.direction.y),
                       std::fabs(ray.direction.z));
    // kz = argmax |d|; ties go to the lower axis so the choice is deterministic.
    kz = (ad.x >= ad.y && ad.x >= ad.z) ? 0 : (ad.y >= ad.z ? 1 : 2);
    kx = kz + 1 == 3 ? 0 : kz + 1;
    ky = kx + 1 == 3 ? 0 : kx + 1;
    const float dz = ray.direction[kz];
#if defined(__SSE2__)
    // The three divisions as one divps: IEEE division is correctly rounded per lane and
    // -a / b == (-a) / b exactly, so the results are those of the scalar lines below, for a
    // third of the latency every query pays.
    alignas(16) float q[4];
    _mm_store_ps(q, _mm_div_ps(_mm_setr_ps(-ray.direction[kx], -ray.direction[ky], 1.f, 1.f),
                               _mm_set1_ps(dz)));
    sx = q[0];
    sy = q[1];
    sz = q[2];
#else
    sx = -ray.direction[kx] / dz;
    sy = -ray.direction[ky] / dz;
    sz = 1.f / dz;
#endif
}

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
