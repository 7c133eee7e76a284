#pragma once
/// \file TriangleIntersection.h
/// Watertight ray/triangle test (Woop, Benthin & Wald 2013, as in pbrt-v4): no ray passes between
/// two triangles sharing an edge or a vertex. Exposed for tests; the tracer uses the same code.

#include <mvcl/core/Export.h>

#include <mvcl/tracer/Ray.h>

#include <glm/vec3.hpp>

#include <cmath>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

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

/// Inline, and always inlined (GCC, clang) like hitPrecedes(): the tracer's kernels, compiled once
/// per instruction set, make one per query in their own instruction set and must not share an
/// out-of-line copy (out of line, the call was 2 % of a cube-in-cube frame's instructions).
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
inline WatertightRay::WatertightRay(const Ray &ray) : origin(ray.origin) {
    const float ax = std::fabs(ray.direction.x), ay = std::fabs(ray.direction.y), az = std::fabs(ray.direction.z);
    // kz = argmax |d|; ties go to the lower axis so the choice is deterministic.
    kz = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2);
    kx = kz + 1 == 3 ? 0 : kz + 1;
    ky = kx + 1 == 3 ? 0 : kx + 1;
    const float dz = ray.direction[kz];
#if defined(__SSE__)
    // The three divisions as one divps: IEEE division is correctly rounded per lane and
    // -a / b == (-a) / b exactly, so the results are those of the scalar lines below, for a
    // third of the latency every query pays.
    alignas(16) float q[4];
    _mm_store_ps(q, _mm_div_ps(_mm_setr_ps(-ray.direction[kx], -ray.direction[ky], 1.f, 1.f), _mm_set1_ps(dz)));
    sx = q[0];
    sy = q[1];
    sz = q[2];
#else
    sx = -ray.direction[kx] / dz;
    sy = -ray.direction[ky] / dz;
    sz = 1.f / dz;
#endif
}

/// Hit with tMin < t < tMax (the lower bound is conservative so t > 0 is guaranteed when tMin = 0).
MVCL_EXPORT bool intersectTriangle(const WatertightRay &ray, const glm::vec3 &p0, const glm::vec3 &p1,
                       const glm::vec3 &p2, float tMin, float tMax, TriangleHit &hit);

/// Convenience overload building the WatertightRay.
MVCL_EXPORT bool intersectTriangle(const Ray &ray, const glm::vec3 &p0, const glm::vec3 &p1,
                       const glm::vec3 &p2, float tMin, float tMax, TriangleHit &hit);

} // namespace mvcl
