#pragma once
/// \file EllipseCoverage4_p.h
/// Private to LensRegion: the coverage of a feathered ellipse at four points at once.
///
/// Most of compose()'s time on an ellipse's edge is the nearest-point iteration, a chain of
/// square roots and divisions that a single pixel cannot overlap. Four pixels in the lanes of
/// one SSE register run that chain side by side. Each lane performs exactly the IEEE operations
/// of the scalar code in LensRegion.cpp (ellipseSignedDistance() and the feather ramp of
/// coverage()) in the same order, with comparisons and selects where the scalar code branches,
/// and products kept unfused (unfused() as in the tracer's 4-wide kernel), so a lane's result
/// is bit-identical to the scalar one. LensRegion::coverage() itself goes through this kernel,
/// so the two cannot drift apart whatever a build does to contraction.

#include <mvcl/core/FloatBits.h>

#if defined(__SSE2__)
#include <emmintrin.h>

namespace mvcl::detail {

/// A feathered ellipse in pixels: centre, radii (both > 0), feather (> 0).
struct EllipseCoverageShape {
    float centerX, centerY;
    float radiusX, radiusY;
    float feather;
};

namespace ellipse4 {

inline __m128 mul(__m128 a, __m128 b) { return unfused(_mm_mul_ps(a, b)); }
inline __m128 select(__m128 mask, __m128 ifTrue, __m128 ifFalse) {
    return _mm_or_ps(_mm_and_ps(mask, ifTrue), _mm_andnot_ps(mask, ifFalse));
}
/// glm::length of (x, y): sqrt(x·x + y·y).
inline __m128 length(__m128 x, __m128 y) { return _mm_sqrt_ps(_mm_add_ps(mul(x, x), mul(y, y))); }
inline __m128 negate(__m128 x) { return _mm_xor_ps(x, _mm_set1_ps(-0.f)); }
/// glm::abs: x ≥ 0 ? x : −x.
inline __m128 absolute(__m128 x) { return select(_mm_cmpge_ps(x, _mm_setzero_ps()), x, negate(x)); }
/// glm::max(x, lo) = x < lo ? lo : x and glm::min(x, hi) = hi < x ? hi : x (NaN passes).
inline __m128 atLeast(__m128 x, __m128 lo) { return select(_mm_cmplt_ps(x, lo), lo, x); }
inline __m128 atMost(__m128 x, __m128 hi) { return select(_mm_cmplt_ps(hi, x), hi, x); }

} // namespace ellipse4

/// coverage()'s first step at four points: the implicit equation settles most of them. Returns
/// their coverage (1 deep inside, 0 outside) and in `unsettled` the lanes (bit i = lane i) that
/// need ellipseRamp4().
inline __m128 ellipseSettled4(const EllipseCoverageShape &e, __m128 x, __m128 y, int &unsettled) {
    using namespace ellipse4;
    const __m128 one = _mm_set1_ps(1.f);
    const __m128 qx = absolute(_mm_sub_ps(x, _mm_set1_ps(e.centerX)));
    const __m128 qy = absolute(_mm_sub_ps(y, _mm_set1_ps(e.centerY)));
    const __m128 sx = _mm_div_ps(qx, _mm_set1_ps(e.radiusX)), sy = _mm_div_ps(qy, _mm_set1_ps(e.radiusY));
    const __m128 radiusSquared = _mm_add_ps(mul(sx, sx), mul(sy, sy));
    const __m128 inside = _mm_cmple_ps(radiusSquared, one); // false for NaN, as !(r² ≤ 1)
    // A point at normalised radius r < 1 is at least (1 − r)·(smaller radius) inside.
    const float smallerRadius = e.radiusY < e.radiusX ? e.radiusY : e.radiusX;
    const __m128 gap = mul(_mm_sub_ps(one, _mm_sqrt_ps(radiusSquared)), _mm_set1_ps(smallerRadius));
    const __m128 deepInside = _mm_and_ps(inside, _mm_cmpge_ps(gap, _mm_set1_ps(e.feather)));
    unsettled = _mm_movemask_ps(_mm_andnot_ps(deepInside, inside));
    return _mm_and_ps(deepInside, one);
}

/// The rest of coverage() for points inside the ellipse but within a feather (or so) of its
/// edge: ellipseSignedDistance()'s iteration (Chatfield's, on the evolute, first quadrant) and
/// the feather ramp. Runs `Chains` groups of four points side by side: the iteration is one
/// long chain of divisions and square roots, and independent chains fill the gaps in it.
template <int Chains>
inline void ellipseRamp4(const EllipseCoverageShape &e, const __m128 (&x)[Chains], __m128 y,
                         __m128 (&coverage)[Chains]) {
    using namespace ellipse4;
    const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.f);
    const __m128 a = _mm_set1_ps(e.radiusX), b = _mm_set1_ps(e.radiusY);
    const float aa = mulUnfused(e.radiusX, e.radiusX), bb = mulUnfused(e.radiusY, e.radiusY);
    const __m128 aaMinusBb = _mm_set1_ps(aa - bb), bbMinusAa = _mm_set1_ps(bb - aa);
    const __m128 qy = absolute(_mm_sub_ps(y, _mm_set1_ps(e.centerY)));
    __m128 qx[Chains], tx[Chains], ty[Chains];
    for (int c = 0; c < Chains; ++c) {
        qx[c] = absolute(_mm_sub_ps(x[c], _mm_set1_ps(e.centerX)));
        tx[c] = ty[c] = _mm_set1_ps(0.70710678f);
    }
    for (int iteration = 0; iteration < 4; ++iteration) {
        for (int c = 0; c < Chains; ++c) {
            const __m128 onX = mul(a, tx[c]), onY = mul(b, ty[c]);
            const __m128 evoluteX = _mm_div_ps(mul(mul(mul(aaMinusBb, tx[c]), tx[c]), tx[c]), a);
            const __m128 evoluteY = _mm_div_ps(mul(mul(mul(bbMinusAa, ty[c]), ty[c]), ty[c]), b);
            const __m128 r = length(_mm_sub_ps(onX, evoluteX), _mm_sub_ps(onY, evoluteY));
            const __m128 wx = _mm_sub_ps(qx[c], evoluteX), wy = _mm_sub_ps(qy, evoluteY);
            const __m128 toPoint = length(wx, wy);
            // Lanes where the scalar code takes the other branch divide by 1 instead of 0.
            const __m128 reaches = _mm_cmpgt_ps(toPoint, zero);
            const __m128 scale = _mm_div_ps(r, select(reaches, toPoint, one));
            const __m128 towardsX = select(reaches, mul(wx, scale), zero);
            const __m128 towardsY = select(reaches, mul(wy, scale), zero);
            const __m128 ux = atMost(atLeast(_mm_div_ps(_mm_add_ps(towardsX, evoluteX), a), zero), one);
            const __m128 uy = atMost(atLeast(_mm_div_ps(_mm_add_ps(towardsY, evoluteY), b), zero), one);
            const __m128 norm = length(ux, uy);
            const __m128 normal = _mm_cmpgt_ps(norm, zero);
            const __m128 divisor = select(normal, norm, one);
            tx[c] = select(normal, _mm_div_ps(ux, divisor), one);
            ty[c] = select(normal, _mm_div_ps(uy, divisor), zero);
        }
    }
    for (int c = 0; c < Chains; ++c) {
        // Inside, the signed distance is this distance; the ramp is std::min(d / feather, 1)
        // through smoothstep, and 0 where the distance is not positive.
        const __m128 distance = length(_mm_sub_ps(qx[c], mul(a, tx[c])), _mm_sub_ps(qy, mul(b, ty[c])));
        const __m128 t = atMost(_mm_div_ps(distance, _mm_set1_ps(e.feather)), one);
        const __m128 smooth = mul(mul(t, t), _mm_sub_ps(_mm_set1_ps(3.f), mul(_mm_set1_ps(2.f), t)));
        coverage[c] = select(_mm_cmpgt_ps(distance, zero), smooth, zero);
    }
}

} // namespace mvcl::detail

#endif
