#pragma once
// Private: sphere and plane intersection in double precision. Spheres and planes are few, so
// double costs nothing measurable and makes t accurate to float rounding (spawned rays offset by
// the error bounds in interaction() then never re-hit the surface).

#include "KernelIsa.h"

#include <glm/vec3.hpp>

#include <cmath>
#include <utility>

#if defined(__AVX__)
#include <immintrin.h>
#endif

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

/// sphereRoots() for the four lanes of a PrimBlock at once (centres in `cx`, `cy`, `cz`, radii in
/// `radius`, one float per lane), for the lanes of `lanes` (bits 0–3): returns the bits of the
/// lanes with two roots, their roots in t0[lane] ≤ t1[lane]. With AVX every lane runs in one
/// 256-bit register the operations sphereRoots() runs, in its order (correctly rounded
/// add, sub, mul, div and sqrt, no contraction), so the roots are the same bits; a sphere leaf
/// was two scalar chains of three divisions and a root each, most of a leaf's instructions.
inline int sphereRoots4(const glm::vec3 &origin, const glm::vec3 &direction, const float *cx, const float *cy,
                        const float *cz, const float *radius, int lanes, double t0[4], double t1[4]) {
#if defined(__AVX__)
    const __m256d fx = _mm256_sub_pd(_mm256_set1_pd(origin.x), _mm256_cvtps_pd(_mm_load_ps(cx)));
    const __m256d fy = _mm256_sub_pd(_mm256_set1_pd(origin.y), _mm256_cvtps_pd(_mm_load_ps(cy)));
    const __m256d fz = _mm256_sub_pd(_mm256_set1_pd(origin.z), _mm256_cvtps_pd(_mm_load_ps(cz)));
    const double dxs = direction.x, dys = direction.y, dzs = direction.z;
    const __m256d dx = _mm256_set1_pd(dxs), dy = _mm256_set1_pd(dys), dz = _mm256_set1_pd(dzs);
    const __m256d a = _mm256_set1_pd(dxs * dxs + dys * dys + dzs * dzs);
    const __m256d b = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(fx, dx), _mm256_mul_pd(fy, dy)), _mm256_mul_pd(fz, dz));
    const __m256d r = _mm256_cvtps_pd(_mm_load_ps(radius));
    const __m256d rr = _mm256_mul_pd(r, r);
    const __m256d c = _mm256_sub_pd(
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(fx, fx), _mm256_mul_pd(fy, fy)), _mm256_mul_pd(fz, fz)), rr);
    const __m256d s = _mm256_div_pd(b, a);
    const __m256d lx = _mm256_sub_pd(fx, _mm256_mul_pd(s, dx));
    const __m256d ly = _mm256_sub_pd(fy, _mm256_mul_pd(s, dy));
    const __m256d lz = _mm256_sub_pd(fz, _mm256_mul_pd(s, dz));
    const __m256d disc = _mm256_sub_pd(
        rr, _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(lx, lx), _mm256_mul_pd(ly, ly)), _mm256_mul_pd(lz, lz)));
    const __m256d zero = _mm256_setzero_pd();
    int roots = _mm256_movemask_pd(_mm256_cmp_pd(disc, zero, _CMP_GE_OQ)) & lanes;
    if (!roots) return 0;
    // copysign(√(a·disc), b): the root is +0, positive or NaN (lanes without roots), so b's sign
    // bit or-ed in is copysign's result.
    const __m256d sign = _mm256_set1_pd(-0.0);
    const __m256d root = _mm256_sqrt_pd(_mm256_mul_pd(a, disc));
    const __m256d q = _mm256_xor_pd(_mm256_add_pd(b, _mm256_or_pd(root, _mm256_and_pd(b, sign))), sign);
    roots &= ~_mm256_movemask_pd(_mm256_cmp_pd(q, zero, _CMP_EQ_OQ));
    if (!roots) return 0;
    const __m256d u = _mm256_div_pd(c, q), v = _mm256_div_pd(q, a);
    // if (t0 > t1) swap: min and max with the scalar code's choice on NaN or equal values.
    const __m256d swap = _mm256_cmp_pd(u, v, _CMP_GT_OQ);
    _mm256_storeu_pd(t0, _mm256_blendv_pd(u, v, swap));
    _mm256_storeu_pd(t1, _mm256_blendv_pd(v, u, swap));
    return roots;
#else
    int roots = 0;
    for (int lane = 0; lane < 4; ++lane) {
        if (!((lanes >> lane) & 1)) continue;
        double t[2];
        if (sphereRoots(origin, direction, glm::vec3(cx[lane], cy[lane], cz[lane]), radius[lane], t) != 2) continue;
        t0[lane] = t[0];
        t1[lane] = t[1];
        roots |= 1 << lane;
    }
    return roots;
#endif
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
