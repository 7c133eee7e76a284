#pragma once
// Private: the watertight test of WatertightTriangle.h on the four lanes of a PrimBlock at once.
// Every lane runs exactly the scalar arithmetic (same IEEE operations in the same order; no FMA:
// every product passes through mulUnfused4(), like the scalar code's mulUnfused(); correctly
// rounded division, maxps/andps for max3/fabs), so a lane's
// t and barycentrics are bit-identical to watertightIntersect(). Lanes where an edge function
// is zero are handed to watertightIntersect() itself for its exact double-precision fallback.

#include "KernelIsa.h"
#include "PrimBlock.h"
#include "WatertightTriangle.h"

#include <mvcl/core/FloatBits.h>
#include <mvcl/tracer/TriangleIntersection.h>

#include <bit>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mvcl::detail {

struct TriangleHit4 {
    alignas(16) float t[4];
    alignas(16) float tError[4]; ///< δt of each lane (TriangleHit::tError)
    alignas(16) float b0[4];
    alignas(16) float b1[4];
    alignas(16) float b2[4];
};

/// The per-ray constants of the 4-wide test, broadcast once per query (not once per block).
struct WatertightRay4 {
    const WatertightRay &ray;
#if defined(__SSE2__)
    __m128 ox, oy, oz; ///< origin, permuted like the ray
    __m128 sx, sy, sz;

    MVCL_KERNEL_INLINE explicit WatertightRay4(const WatertightRay &r)
        : ray(r), ox(_mm_set1_ps(r.origin[r.kx])), oy(_mm_set1_ps(r.origin[r.ky])),
          oz(_mm_set1_ps(r.origin[r.kz])), sx(_mm_set1_ps(r.sx)), sy(_mm_set1_ps(r.sy)),
          sz(_mm_set1_ps(r.sz)) {}
#else
    MVCL_KERNEL_INLINE explicit WatertightRay4(const WatertightRay &r) : ray(r) {}
#endif
};

// The kernel itself: one copy per instruction set that compiles it (KernelIsa.h).
inline namespace MVCL_ISA_NAMESPACE {

#if defined(__SSE2__)
/// _mm_mul_ps rounded on its own: GCC and clang implement it as a plain vector product, which
/// -ffp-contract=fast would fuse with the following _mm_add_ps (see unfused() in FloatBits.h).
inline __m128 mulUnfused4(__m128 a, __m128 b) { return unfused(_mm_mul_ps(a, b)); }
#endif

/// Tests the lanes set in `lanes` (bit i = lane i) against the ray; returns the bits of the lanes
/// hit with their results in `hit`. tMax plays the same role as in watertightIntersect().
/// Barycentrics = false leaves hit.b0..b2 of the vector lanes unwritten: any-hit queries only need
/// t, which is the same arithmetic either way. OrderingError = false leaves hit.tError of the
/// vector lanes unwritten: only layer priority reads it.
template <bool Barycentrics = true, bool OrderingError = false>
MVCL_KERNEL_INLINE int watertightIntersect4(const WatertightRay4 &r4, const PrimBlock &b, int lanes, float tMax,
                                TriangleHit4 &hit) {
    const WatertightRay &r = r4.ray;
#if defined(__SSE2__)
    const __m128 zero = _mm_setzero_ps();
    const __m128 absMask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    const __m128 ox = r4.ox, oy = r4.oy, oz = r4.oz;
    const __m128 sx = r4.sx, sy = r4.sy, sz = r4.sz;

    // The shear of WatertightTriangle.h, per vertex.
    const __m128 p0z = _mm_sub_ps(_mm_load_ps(b.v[0][r.kz]), oz);
    const __m128 p1z = _mm_sub_ps(_mm_load_ps(b.v[1][r.kz]), oz);
    const __m128 p2z = _mm_sub_ps(_mm_load_ps(b.v[2][r.kz]), oz);
    const __m128 p0x = _mm_add_ps(_mm_sub_ps(_mm_load_ps(b.v[0][r.kx]), ox), mulUnfused4(sx, p0z));
    const __m128 p0y = _mm_add_ps(_mm_sub_ps(_mm_load_ps(b.v[0][r.ky]), oy), mulUnfused4(sy, p0z));
    const __m128 p1x = _mm_add_ps(_mm_sub_ps(_mm_load_ps(b.v[1][r.kx]), ox), mulUnfused4(sx, p1z));
    const __m128 p1y = _mm_add_ps(_mm_sub_ps(_mm_load_ps(b.v[1][r.ky]), oy), mulUnfused4(sy, p1z));
    const __m128 p2x = _mm_add_ps(_mm_sub_ps(_mm_load_ps(b.v[2][r.kx]), ox), mulUnfused4(sx, p2z));
    const __m128 p2y = _mm_add_ps(_mm_sub_ps(_mm_load_ps(b.v[2][r.ky]), oy), mulUnfused4(sy, p2z));

    const __m128 e0 = _mm_sub_ps(mulUnfused4(p1x, p2y), mulUnfused4(p1y, p2x));
    const __m128 e1 = _mm_sub_ps(mulUnfused4(p2x, p0y), mulUnfused4(p2y, p0x));
    const __m128 e2 = _mm_sub_ps(mulUnfused4(p0x, p1y), mulUnfused4(p0y, p1x));

    // Lanes with a zero edge function go to the scalar test (double fallback) below.
    const int onEdge =
        _mm_movemask_ps(_mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(e0, zero), _mm_cmpeq_ps(e1, zero)),
                                  _mm_cmpeq_ps(e2, zero))) &
        lanes;
    const __m128 anyNeg =
        _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(e0, zero), _mm_cmplt_ps(e1, zero)), _mm_cmplt_ps(e2, zero));
    const __m128 anyPos =
        _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(e0, zero), _mm_cmpgt_ps(e1, zero)), _mm_cmpgt_ps(e2, zero));
    // Both signs present: the ray passes outside the triangle.
    __m128 reject = _mm_and_ps(anyNeg, anyPos);
    const __m128 det = _mm_add_ps(_mm_add_ps(e0, e1), e2);
    reject = _mm_or_ps(reject, _mm_cmpeq_ps(det, zero));
    int candidates = lanes & ~onEdge & ~_mm_movemask_ps(reject);

    int hits = 0;
    if (candidates) {
        const __m128 z0 = mulUnfused4(sz, p0z);
        const __m128 z1 = mulUnfused4(sz, p1z);
        const __m128 z2 = mulUnfused4(sz, p2z);
        const __m128 tScaled =
            _mm_add_ps(_mm_add_ps(mulUnfused4(e0, z0), mulUnfused4(e1, z1)), mulUnfused4(e2, z2));
        const __m128 bound = mulUnfused4(_mm_set1_ps(tMax * kEarlyRejectSlack), det);
        const __m128 detNeg = _mm_cmplt_ps(det, zero);
        const __m128 detPos = _mm_cmpgt_ps(det, zero);
        reject = _mm_or_ps(
            _mm_and_ps(detNeg, _mm_or_ps(_mm_cmpge_ps(tScaled, zero), _mm_cmplt_ps(tScaled, bound))),
            _mm_and_ps(detPos, _mm_or_ps(_mm_cmple_ps(tScaled, zero), _mm_cmpgt_ps(tScaled, bound))));
        candidates &= ~_mm_movemask_ps(reject);
        if (candidates) {
            const __m128 invDet = _mm_div_ps(_mm_set1_ps(1.f), det);
            const __m128 t = mulUnfused4(tScaled, invDet);

            // Conservative t > δt, term by term as in watertightIntersect().
            const __m128 maxZt = _mm_max_ps(
                _mm_max_ps(_mm_and_ps(z0, absMask), _mm_and_ps(z1, absMask)), _mm_and_ps(z2, absMask));
            const __m128 deltaZ = mulUnfused4(_mm_set1_ps(gamma(3)), maxZt);
            const __m128 maxXt = _mm_max_ps(
                _mm_max_ps(_mm_and_ps(p0x, absMask), _mm_and_ps(p1x, absMask)), _mm_and_ps(p2x, absMask));
            const __m128 maxYt = _mm_max_ps(
                _mm_max_ps(_mm_and_ps(p0y, absMask), _mm_and_ps(p1y, absMask)), _mm_and_ps(p2y, absMask));
            // Shear rounding bounded by |sx|·max|pz| (see watertightIntersect()).
            const __m128 maxPz = _mm_max_ps(
                _mm_max_ps(_mm_and_ps(p0z, absMask), _mm_and_ps(p1z, absMask)), _mm_and_ps(p2z, absMask));
            const __m128 deltaX = mulUnfused4(
                _mm_set1_ps(gamma(5)), _mm_add_ps(maxXt, mulUnfused4(_mm_and_ps(sx, absMask), maxPz)));
            const __m128 deltaY = mulUnfused4(
                _mm_set1_ps(gamma(5)), _mm_add_ps(maxYt, mulUnfused4(_mm_and_ps(sy, absMask), maxPz)));
            const __m128 deltaE = mulUnfused4(
                _mm_set1_ps(2.f),
                _mm_add_ps(_mm_add_ps(mulUnfused4(mulUnfused4(_mm_set1_ps(gamma(2)), maxXt), maxYt),
                                      mulUnfused4(deltaY, maxXt)),
                           mulUnfused4(deltaX, maxYt)));
            const __m128 maxE = _mm_max_ps(
                _mm_max_ps(_mm_and_ps(e0, absMask), _mm_and_ps(e1, absMask)), _mm_and_ps(e2, absMask));
            const __m128 deltaT = mulUnfused4(
                mulUnfused4(
                    _mm_set1_ps(3.f),
                    _mm_add_ps(_mm_add_ps(mulUnfused4(mulUnfused4(_mm_set1_ps(gamma(3)), maxE), maxZt),
                                          mulUnfused4(deltaE, maxZt)),
                               mulUnfused4(deltaZ, maxE))),
                _mm_and_ps(invDet, absMask));
            // Accept t > 0 and not t ≤ δt, with the NaN behaviour of the scalar `if`s.
            const __m128 accept = _mm_and_ps(_mm_cmpgt_ps(t, zero), _mm_cmpnle_ps(t, deltaT));
            hits = candidates & _mm_movemask_ps(accept);
            if (hits) {
                _mm_store_ps(hit.t, t);
                if (OrderingError) {
                    // orderingError() lane by lane.
                    const __m128 spread = _mm_add_ps(
                        _mm_add_ps(_mm_and_ps(_mm_sub_ps(z0, t), absMask), _mm_and_ps(_mm_sub_ps(z1, t), absMask)),
                        _mm_and_ps(_mm_sub_ps(z2, t), absMask));
                    const __m128 g3 = _mm_set1_ps(gamma(3));
                    const __m128 terms = _mm_add_ps(
                        _mm_add_ps(mulUnfused4(g3, _mm_mul_ps(_mm_set1_ps(2.f), maxZt)),
                                   mulUnfused4(g3, _mm_and_ps(t, absMask))),
                        mulUnfused4(mulUnfused4(deltaE, spread), _mm_and_ps(invDet, absMask)));
                    _mm_store_ps(hit.tError, _mm_mul_ps(_mm_set1_ps(2.f), terms));
                }
                if (Barycentrics) {
                    _mm_store_ps(hit.b0, _mm_mul_ps(e0, invDet));
                    _mm_store_ps(hit.b1, _mm_mul_ps(e1, invDet));
                    _mm_store_ps(hit.b2, _mm_mul_ps(e2, invDet));
                }
            }
        }
    }
    int rest = onEdge;
#else
    int hits = 0;
    int rest = lanes;
#endif
    while (rest) {
        const int lane = std::countr_zero(unsigned(rest));
        rest &= rest - 1;
        TriangleHit h;
        if (!watertightIntersect(r, b.vertex(lane, 0), b.vertex(lane, 1), b.vertex(lane, 2), tMax,
                                 h))
            continue;
        hit.t[lane] = h.t;
        hit.tError[lane] = h.tError;
        hit.b0[lane] = h.b0;
        hit.b1[lane] = h.b1;
        hit.b2[lane] = h.b2;
        hits |= 1 << lane;
    }
    return hits;
}

} // namespace MVCL_ISA_NAMESPACE
} // namespace mvcl::detail
