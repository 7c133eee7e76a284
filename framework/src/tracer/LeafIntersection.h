#pragma once
// Private: the leaf end of traversal, shared by the single-ray walk (WideTraversal.inl), the packet
// walk (PacketTraversal.inl, for leaves holding spheres) and the brute-force oracle: the robust slab
// test of one box, the sphere lane test, the 4-wide triangle test of a leaf's blocks, and the
// candidate Hits they offer to a closest-hit state. Compiled into every kernel unit, one copy per
// instruction set (KernelIsa.h), so that traversal inlines them in its own instruction set.

#include "AnalyticShapes.h"
#include "KernelIsa.h"
#include "PlaneRecord.h"
#include "PrimBlock.h"
#include "RayContext.h"
#include "WatertightTriangle.h"
#include "WatertightTriangle4.h"
#include "WideBvh.h"

#include <mvcl/core/FloatBits.h>
#include <mvcl/tracer/Hit.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mvcl::detail {
inline namespace MVCL_ISA_NAMESPACE {

/// Robust slab test (Ize 2013). Slabs are taken in the ray's sign order, so a ±0 direction
/// component gives ±∞ distances with the right sign; an origin exactly on a slab plane gives
/// 0·∞ = NaN, which the comparisons below discard (the ray lies in the face: treat as inside).
/// The far slabs use invDirFar, which carries the conservative widening (RayContext.h).
inline bool intersectBox(const float *b, const RayContext &c, float tHigh, float &tEntry) {
    const float tx0 = (b[c.nearIdx[0]] - c.ray.origin.x) * c.invDir.x;
    const float ty0 = (b[c.nearIdx[1]] - c.ray.origin.y) * c.invDir.y;
    const float tz0 = (b[c.nearIdx[2]] - c.ray.origin.z) * c.invDir.z;
    const float tx1 = (b[c.farIdx[0]] - c.ray.origin.x) * c.invDirFar.x;
    const float ty1 = (b[c.farIdx[1]] - c.ray.origin.y) * c.invDirFar.y;
    const float tz1 = (b[c.farIdx[2]] - c.ray.origin.z) * c.invDirFar.z;
    // The order of the SIMD node test (maxps(a, b) = a > b ? a : b); tHigh starts the far
    // minimum, as there.
    float tNear = c.tLow;
    tNear = tx0 > tNear ? tx0 : tNear;
    tNear = ty0 > tNear ? ty0 : tNear;
    tNear = tz0 > tNear ? tz0 : tNear;
    float tFar = tHigh;
    tFar = tx1 < tFar ? tx1 : tFar;
    tFar = ty1 < tFar ? ty1 : tFar;
    tFar = tz1 < tFar ? tz1 : tFar;
    tEntry = tNear;
    return tNear <= tFar;
}

/// Error bound of a sphere's or plane's t: the roots are computed in double and rounded to
/// float once, so half an ulp of rounding plus the double arithmetic's far smaller error.
inline float analyticTError(float t) { return gamma(2) * std::fabs(t); }

/// A triangle lane's hit as a candidate Hit (the t range is checked by the caller).
inline Hit triangleCandidate(const PrimInfo &info, float t, float b1, float b2) {
    Hit cand;
    cand.t = t;
    cand.u = b1;
    cand.v = b2;
    cand.kind = GeometryKind::Triangle;
    cand.layer = info.layer;
    cand.geometry = info.geometry;
    cand.primitive = info.primitive;
    return cand;
}

/// A sphere or plane hit: one primitive per geometry, no barycentrics.
inline Hit analyticCandidate(GeometryKind kind, float t, uint8_t layer, uint32_t geometry) {
    Hit cand;
    cand.t = t;
    cand.kind = kind;
    cand.layer = layer;
    cand.geometry = geometry;
    cand.primitive = 0;
    return cand;
}

/// Offers the roots of one sphere (ascending). For closest hit (AnyHit = false) offers its hits to
/// `best` and returns true if it changed; for any hit returns true on the first accepted hit.
template <bool AnyHit, class Best>
inline bool offerSphereRoots(const double roots[2], const PrimInfo &info, const RayContext &c, Best &best) {
    for (int i = 0; i < 2; ++i) {
        const float t = float(roots[i]);
        if (!c.acceptsT(t)) continue;
        const Hit cand = analyticCandidate(GeometryKind::Sphere, t, info.layer, info.geometry);
        if (AnyHit) {
            if (c.acceptsPoint(t, info.layer)) return true;
            continue;
        }
        // The far root cannot do better than the near one, so stop once the near one cannot
        // matter; a near root cut away by a clip volume falls through to the far root.
        if (!best.mayMatter(cand)) return false;
        if (best.offer(c, cand, analyticTError(t))) return true;
    }
    return false;
}

/// Tests the sphere in lane `lane` of a block (offerSphereRoots()'s result).
template <bool AnyHit, class Best>
inline bool testSphere(const PrimBlock &block, int lane, const PrimInfo &info,
                       const RayContext &c, Best &best) {
    double roots[2];
    if (sphereRoots(c.ray.origin, c.ray.direction, block.vertex(lane, 0), block.v[1][0][lane], roots) != 2)
        return false;
    return offerSphereRoots<AnyHit>(roots, info, c, best);
}

/// Tests the planes [planes, planes + count). For closest hit (AnyHit = false) offers their hits to
/// `best` and returns true if it changed; for any hit returns true on the first accepted hit.
template <bool AnyHit, class Best>
inline bool testPlanes(const PlaneRecord *planes, std::size_t count, const RayContext &c, Best &best) {
    bool found = false;
    for (std::size_t i = 0; i < count; ++i) {
        const PlaneRecord &pl = planes[i];
        if (!((c.layerMask >> pl.layer) & 1u)) continue;
        const float t = float(planeT(c.ray.origin, c.ray.direction, pl.normal, pl.offset));
        if (!c.acceptsT(t)) continue;
        if (AnyHit) {
            if (c.acceptsPoint(t, pl.layer)) return true;
            continue;
        }
        found |= best.offer(c, analyticCandidate(GeometryKind::Plane, t, pl.layer, pl.geometry), analyticTError(t));
    }
    return found;
}

/// Bits of the lanes whose triangle is in one of the query's layers.
inline int triangleLanes(const PrimBlock &block, uint32_t layerMask) {
#if defined(__SSE2__)
    const __m128i bits =
        _mm_and_si128(_mm_load_si128(reinterpret_cast<const __m128i *>(block.triangleLayerBit)),
                      _mm_set1_epi32(int(layerMask)));
    return ~_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(bits, _mm_setzero_si128()))) & 0xf;
#else
    int lanes = 0;
    for (int lane = 0; lane < 4; ++lane)
        if (block.triangleLayerBit[lane] & layerMask) lanes |= 1 << lane;
    return lanes;
#endif
}

/// Tests the primitives of one leaf. For closest hit (AnyHit = false) offers the hits to `best`
/// and returns true if it changed; for any hit returns true on the first accepted hit.
template <bool AnyHit, class Best>
MVCL_KERNEL_INLINE bool testLeaf(uint32_t leaf, const PrimBlock *blocks, const PrimInfo *info,
                     const RayContext &c, const WatertightRay4 &wray, Best &best) {
    const uint32_t first = WideLeaf::firstBlock(leaf);
    const uint32_t last = first + WideLeaf::blockCount(leaf);
    bool found = false;
    for (uint32_t b = first; b < last; ++b) {
        const PrimBlock &block = blocks[b];
        const int lanes = triangleLanes(block, c.layerMask);
        if (!lanes) continue;
        // A stale (larger) cap only lets more candidates reach offer(), which orders them
        // exactly; the t of a lane does not depend on the cap.
        const float tCap = AnyHit ? c.tMax : std::min(c.tMax, best.cap());
        TriangleHit4 th;
        int hits = watertightIntersect4<!AnyHit, !AnyHit && Best::kUsesTError>(wray, block, lanes, tCap, th);
        while (hits) {
            const int lane = std::countr_zero(unsigned(hits));
            hits &= hits - 1;
            if (!c.acceptsT(th.t[lane])) continue;
            if (AnyHit) {
                if (c.acceptsPoint(th.t[lane], info[4 * b + lane].layer)) return true;
                continue;
            }
            found |= best.offer(c, triangleCandidate(info[4 * b + lane], th.t[lane], th.b1[lane],
                                                     th.b2[lane]),
                                Best::kUsesTError ? th.tError[lane] : 0.f);
        }
    }
    if (WideLeaf::hasSpheres(leaf)) {
        for (uint32_t b = first; b < last; ++b) {
            int sphereLanes = 0;
            for (int lane = 0; lane < 4; ++lane) {
                const PrimInfo &pi = info[4 * b + lane];
                if (pi.kind == uint8_t(PrimKind::Sphere) && ((c.layerMask >> pi.layer) & 1u))
                    sphereLanes |= 1 << lane;
            }
            if (!sphereLanes) continue;
            // The block's spheres at once; their roots are offered lane by lane, as one by one.
            const PrimBlock &block = blocks[b];
            double t0[4], t1[4];
            for (int rest = sphereRoots4(c.ray.origin, c.ray.direction, block.v[0][0], block.v[0][1], block.v[0][2],
                                         block.v[1][0], sphereLanes, t0, t1);
                 rest; rest &= rest - 1) {
                const int lane = std::countr_zero(unsigned(rest));
                const double roots[2] = {t0[lane], t1[lane]};
                if (offerSphereRoots<AnyHit>(roots, info[4 * b + lane], c, best)) {
                    if (AnyHit) return true;
                    found = true;
                }
            }
        }
    }
    return found;
}

} // namespace MVCL_ISA_NAMESPACE
} // namespace mvcl::detail
