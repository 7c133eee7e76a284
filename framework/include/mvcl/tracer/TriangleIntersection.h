#pragma once
/// \file TriangleIntersection.h
/// Watertight ray/triangle test (Woop, Benthin & Wald 2013, as in pbrt-v4): no ray passes between
/// two triangles sharing an edge or a vertex. Exposed for tests; the tracer uses the same code.

#include <mvcl/core/Export.h>

#include <mvcl/tracer/Ray.h>

#include <glm/vec3.hpp>

namespace mvcl {

struct TriangleHit {
    float t;
    float b0, b1, b2; ///< barycentrics of p0, p1, p2
    /// Bound on |t − the exact t of the float ray and vertices| from the test's error analysis,
    /// made for comparing two hits (the edge functions' error weighted by the triangle's depth
    /// spread; pbrt-v4 §6.8.4's δt, which the test uses to prove t > 0, weighs it with the
    /// distance and is far looser). The tracer's layer priority compares hits with it.
    float tError;
};

/// Per-ray constants of the watertight test (permutation and shear), computed once per ray.
struct MVCL_EXPORT WatertightRay {
    int kx, ky, kz;
    float sx, sy, sz;
    glm::vec3 origin;
    explicit WatertightRay(const Ray &ray);
};

/// Hit with tMin < t < tMax (the lower bound is conservative so t > 0 is guaranteed when tMin = 0).
MVCL_EXPORT bool intersectTriangle(const WatertightRay &ray, const glm::vec3 &p0, const glm::vec3 &p1,
                       const glm::vec3 &p2, float tMin, float tMax, TriangleHit &hit);

/// Convenience overload building the WatertightRay.
MVCL_EXPORT bool intersectTriangle(const Ray &ray, const glm::vec3 &p0, const glm::vec3 &p1,
                       const glm::vec3 &p2, float tMin, float tMax, TriangleHit &hit);

} // namespace mvcl
