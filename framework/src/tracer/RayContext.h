#pragma once
// Private: per-ray constants of traversal and of the query's filters, computed once per query.
// The triangle kernel's WatertightRay is made separately, once the ray enters the scene bounds.

#include "KernelIsa.h"

#include <mvcl/core/FloatBits.h>
#include <mvcl/tracer/Ray.h>
#include <mvcl/tracer/RayQuery.h>
#include <mvcl/tracer/TriangleIntersection.h>

#include <glm/vec3.hpp>

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <limits>

namespace mvcl::detail {

inline constexpr float kInfinity = std::numeric_limits<float>::infinity();
/// Ize 2013: scaling the far slab distance by 1 + 2γ(3) removes every false miss of the box test.
inline constexpr float kBoxFarScale = 1.f + 2.f * gamma(3);
/// Traversal enters boxes up to this relative distance beyond the current closest hit (and
/// before tMin). The watertight test's t and the slab test's t round differently; without the
/// slack a triangle lying exactly on a box face could be culled although its t ties the best
/// hit, and the BVH would then disagree with the brute-force oracle. False hits only cost time.
inline constexpr float kTraversalSlackUp = 1.f + 1.f / 65536.f;
inline constexpr float kTraversalSlackDown = 1.f - 1.f / 65536.f;

/// True if the ray and the range [tMin, tMax] are usable: finite origin and direction, non-zero
/// direction, tMin ≤ tMax, neither NaN.
inline bool isValidQuery(const Ray &ray, float tMin, float tMax) {
#if defined(__SSE2__)
    // The six components in two loads, [ox oy oz dx] and [oz dx dy dz]: x − x is 0 exactly for
    // finite x and NaN for ±∞ and NaN; a few instructions instead of nine branches, which every
    // query paid (most primary rays miss the scene and cost little else).
    static_assert(offsetof(Ray, origin) == 0 && offsetof(Ray, direction) == 12, "six packed floats");
    const char *bytes = reinterpret_cast<const char *>(&ray);
    const __m128 a = _mm_loadu_ps(reinterpret_cast<const float *>(bytes));
    const __m128 b = _mm_loadu_ps(reinterpret_cast<const float *>(bytes + 8));
    const __m128 zero = _mm_setzero_ps();
    const __m128 finite = _mm_and_ps(_mm_cmpeq_ps(_mm_sub_ps(a, a), zero), _mm_cmpeq_ps(_mm_sub_ps(b, b), zero));
    if (_mm_movemask_ps(finite) != 0xf) return false;
    // Lanes 1–3 of b are the direction; −0 counts as zero, as in the scalar test.
    if (!(_mm_movemask_ps(_mm_cmpneq_ps(b, zero)) & 0xe)) return false;
#else
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(ray.origin[k]) || !std::isfinite(ray.direction[k])) return false;
    if (ray.direction.x == 0.f && ray.direction.y == 0.f && ray.direction.z == 0.f) return false;
#endif
    if (std::isnan(tMin) || std::isnan(tMax) || tMin > tMax) return false;
    return tMax > 0.f;
}
inline bool isValidQuery(const Ray &ray, const RayQuery &query) { return isValidQuery(ray, query.tMin, query.tMax); }

struct RayContext {
    Ray ray;
    glm::vec3 invDir;
    /// invDir · kBoxFarScale, for the far slabs only: Ize's widening folded into the reciprocal
    /// instead of a multiply of every box's tFar, which sat on the latency-bound node chain.
    /// Same rounding count as (fl((b − o)·invDir))·s — sub, division, two products — so the
    /// 1 + 2γ(3) bound still covers it; an overflow to ±∞ (|d| below ~3e-39) only widens.
    glm::vec3 invDirFar;
    /// Index into BvhNode::bounds of the slab the ray enters through, per axis. The fourth entry
    /// of this and the next three arrays is padding for the one 128-bit store that writes each.
    int nearIdx[4];
    int farIdx[4];
    /// nearIdx and farIdx as byte offsets of rows of kRowBytes (WideNode::bounds: a row of eight
    /// floats per bound), which the node test adds to a node's address as they are.
    static constexpr uint32_t kRowBytes = 32;
    uint32_t nearRow[4];
    uint32_t farRow[4];
    float tMin;     ///< query lower bound (hits need t ≥ tMin and t > 0)
    float tMax;     ///< query upper bound
    float tLow;     ///< box culling lower bound (with slack)
    uint32_t layerMask;
    const RayQuery *query;
    bool hasClips;

    MVCL_KERNEL_INLINE RayContext(const Ray &r, const RayQuery &q) : RayContext(r, q, q.tMin, q.tMax) {}
    /// The query with its range ending at `rangeEnd` instead of q.tMax (a shadow ray's own length).
    MVCL_KERNEL_INLINE RayContext(const Ray &r, const RayQuery &q, float rangeEnd)
        : RayContext(r, q, q.tMin, rangeEnd) {}
    /// The query with the range [rangeStart, rangeEnd] instead of its own (a step of a walk).
    MVCL_KERNEL_INLINE RayContext(const Ray &r, const RayQuery &q, float rangeStart, float rangeEnd)
        : ray(r), tMin(rangeStart), tMax(rangeEnd), layerMask(q.layerMask), query(&q),
          hasClips(q.clipCount() > 0) {
#if defined(__SSE2__)
        // One divps instead of three divss (same correctly rounded quotients per lane).
        alignas(16) float inv[4];
        const __m128 reciprocal =
            _mm_div_ps(_mm_set1_ps(1.f), _mm_setr_ps(r.direction.x, r.direction.y, r.direction.z, 1.f));
        _mm_store_ps(inv, reciprocal);
        invDir = glm::vec3(inv[0], inv[1], inv[2]);
        // IEEE division keeps the sign of zero: 1/(−0) = −∞, so the slab order taken from the sign
        // bits of 1/d is right for ±0 components too. Arithmetic on the sign bit, not a choice:
        // compiled as branches, the three signs of incoherent rays (diffuse bounces) were
        // mispredicted half of the time. The three axes at once: 3 where 1/d is negative, added
        // to the near index and taken from the far one (a third of the scalar instructions).
        const __m128i flip =
            _mm_and_si128(_mm_srai_epi32(_mm_castps_si128(reciprocal), 31), _mm_set1_epi32(3));
        const __m128i nearV = _mm_add_epi32(_mm_setr_epi32(0, 1, 2, 0), flip);
        const __m128i farV = _mm_sub_epi32(_mm_setr_epi32(3, 4, 5, 0), flip);
        _mm_storeu_si128(reinterpret_cast<__m128i *>(nearIdx), nearV);
        _mm_storeu_si128(reinterpret_cast<__m128i *>(farIdx), farV);
        static_assert(kRowBytes == 32, "the shift below");
        _mm_storeu_si128(reinterpret_cast<__m128i *>(nearRow), _mm_slli_epi32(nearV, 5));
        _mm_storeu_si128(reinterpret_cast<__m128i *>(farRow), _mm_slli_epi32(farV, 5));
#else
        for (int k = 0; k < 3; ++k) invDir[k] = 1.f / r.direction[k];
        for (int k = 0; k < 3; ++k) {
            const int negative = int(std::bit_cast<uint32_t>(invDir[k]) >> 31);
            nearIdx[k] = k + 3 * negative;
            farIdx[k] = k + 3 - 3 * negative;
            nearRow[k] = uint32_t(nearIdx[k]) * kRowBytes;
            farRow[k] = uint32_t(farIdx[k]) * kRowBytes;
        }
        nearIdx[3] = farIdx[3] = 0;
        nearRow[3] = farRow[3] = 0;
#endif
        invDirFar = invDir * kBoxFarScale;
        tLow = tMin > 0.f ? tMin * kTraversalSlackDown : 0.f;
    }

    /// The query's t-range test, applied to every candidate (never by the box test).
    MVCL_KERNEL_INLINE bool acceptsT(float t) const { return t > 0.f && t >= tMin && t <= tMax && t < kInfinity; }
    MVCL_KERNEL_INLINE bool acceptsPoint(float t, uint32_t layer) const { return !hasClips || clipsAccept(t, layer); }
    /// The query's clip volumes at the point at t, for a hit on `layer`. Out of line, in baseline code (RayContext.cpp):
    /// the kernels of every instruction set call this one copy instead of each compiling the
    /// public headers' inline clip tests, which they could then share (KernelIsa.h). Only
    /// queries with clip volumes pay for the call.
    bool clipsAccept(float t, uint32_t layer) const;
};

/// RayContext::clipsAccept() for a ray without a RayContext (a lane of a packet): the same
/// baseline copy.
bool clipsAcceptAt(const RayQuery &query, const Ray &ray, float t, uint32_t layer);

} // namespace mvcl::detail
