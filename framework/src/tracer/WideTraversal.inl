#pragma once
// Private: the wide-BVH traversal loop, compiled by two translation units: TraversalSse2.cpp
// (MVCL_TRAVERSAL_AVX2 0: two 4-lane SSE halves per node, the baseline of every x86-64 CPU) and
// TraversalAvx2.cpp (MVCL_TRAVERSAL_AVX2 1, built with -mavx2: all eight lanes in one 256-bit
// test). Each exports the loop as a table (KernelTables.h) and a Tracer picks one at run time.
// Both node tests do the same IEEE min/max/sub/mul per lane as the scalar intersectBox(), so the
// two variants visit the same nodes and return bit-identical hits (the tests force each and
// compare). Everything here lands in the unit's own namespace (KernelIsa.h).

#include "KernelIsa.h"
#include "LayerPriorityHit.h"
#include "LeafIntersection.h"
#include "NearestHit.h"
#include "PlaneRecord.h"
#include "RayContext.h"
#include "WatertightTriangle4.h"
#include "WideBvh.h"

#include <mvcl/tracer/Hit.h>
#include <mvcl/tracer/Ray.h>
#include <mvcl/tracer/RayQuery.h>
#include <mvcl/tracer/TriangleIntersection.h>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <utility>

#if !defined(MVCL_TRAVERSAL_AVX2)
#error "the including unit chooses the variant: MVCL_TRAVERSAL_AVX2 0 or 1"
#endif

#if MVCL_TRAVERSAL_AVX2
#include <immintrin.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mvcl::detail {
inline namespace MVCL_ISA_NAMESPACE {

/// The per-ray constants of intersectNode(), broadcast once per query.
struct NodeRay {
    const RayContext &c;
    uint32_t layerMask;
#if MVCL_TRAVERSAL_AVX2
    __m256 ox, oy, oz, ix, iy, iz, fx, fy, fz, tLow; ///< f: invDirFar

    explicit NodeRay(const RayContext &ctx)
        : c(ctx), layerMask(ctx.layerMask), ox(_mm256_set1_ps(ctx.ray.origin.x)), oy(_mm256_set1_ps(ctx.ray.origin.y)),
          oz(_mm256_set1_ps(ctx.ray.origin.z)), ix(_mm256_set1_ps(ctx.invDir.x)),
          iy(_mm256_set1_ps(ctx.invDir.y)), iz(_mm256_set1_ps(ctx.invDir.z)),
          fx(_mm256_set1_ps(ctx.invDirFar.x)), fy(_mm256_set1_ps(ctx.invDirFar.y)),
          fz(_mm256_set1_ps(ctx.invDirFar.z)),
          tLow(_mm256_set1_ps(ctx.tLow)) {}
#elif defined(__SSE2__)
    __m128 ox, oy, oz, ix, iy, iz, fx, fy, fz, tLow; ///< f: invDirFar

    explicit NodeRay(const RayContext &ctx)
        : c(ctx), layerMask(ctx.layerMask), ox(_mm_set1_ps(ctx.ray.origin.x)), oy(_mm_set1_ps(ctx.ray.origin.y)),
          oz(_mm_set1_ps(ctx.ray.origin.z)), ix(_mm_set1_ps(ctx.invDir.x)),
          iy(_mm_set1_ps(ctx.invDir.y)), iz(_mm_set1_ps(ctx.invDir.z)),
          fx(_mm_set1_ps(ctx.invDirFar.x)), fy(_mm_set1_ps(ctx.invDirFar.y)),
          fz(_mm_set1_ps(ctx.invDirFar.z)),
          tLow(_mm_set1_ps(ctx.tLow)) {}
#else
    explicit NodeRay(const RayContext &ctx) : c(ctx), layerMask(ctx.layerMask) {}
#endif
};

static_assert(sizeof(WideNode::bounds[0]) == RayContext::kRowBytes);

/// The row of n.bounds at byte offset `offset` (RayContext::nearRow, RayContext::farRow): the
/// offsets are made once per query, where indices took a sign extension and a shift per row at
/// every node. Read through the context rather than copied: the copies were spilled to the
/// stack anyway, and the copying was a dozen instructions of every query's set-up.
MVCL_KERNEL_INLINE const float *slabRow(const WideNode &n, uint32_t offset) {
    return reinterpret_cast<const float *>(reinterpret_cast<const char *>(n.bounds) + offset);
}

#if !MVCL_TRAVERSAL_AVX2 && defined(__SSE2__)
/// Lanes [first, first + 4) of intersectNode().
inline int intersectHalf(const WideNode &n, const NodeRay &r, int first, __m128 tHigh,
                         float *tNear4) {
    const __m128 tx0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(slabRow(n, r.c.nearRow[0]) + first), r.ox), r.ix);
    const __m128 ty0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(slabRow(n, r.c.nearRow[1]) + first), r.oy), r.iy);
    const __m128 tz0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(slabRow(n, r.c.nearRow[2]) + first), r.oz), r.iz);
    const __m128 tx1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(slabRow(n, r.c.farRow[0]) + first), r.ox), r.fx);
    const __m128 ty1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(slabRow(n, r.c.farRow[1]) + first), r.oy), r.fy);
    const __m128 tz1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(slabRow(n, r.c.farRow[2]) + first), r.oz), r.fz);
    // maxps/minps return the second operand when either is NaN: the running value survives a
    // 0·∞ lane exactly like the scalar comparisons in intersectBox.
    __m128 tNear = _mm_max_ps(tx0, r.tLow);
    tNear = _mm_max_ps(ty0, tNear);
    tNear = _mm_max_ps(tz0, tNear);
    // tHigh starts the far minimum (it is never NaN, as ∞ was): one compare instead of two.
    __m128 tFar = _mm_min_ps(tx1, tHigh);
    tFar = _mm_min_ps(ty1, tFar);
    tFar = _mm_min_ps(tz1, tFar);
    const __m128 ok = _mm_cmple_ps(tNear, tFar);
    _mm_storeu_ps(tNear4, tNear);
    const __m128i lm =
        _mm_and_si128(_mm_load_si128(reinterpret_cast<const __m128i *>(n.layerMask + first)),
                      _mm_set1_epi32(int(r.layerMask)));
    const int masked = _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(lm, _mm_setzero_si128())));
    return _mm_movemask_ps(ok) & ~masked;
}
#endif

/// Slab test of the children of a node (the arithmetic of intersectBox, lane by lane; the far slabs
/// carry the widening in invDirFar, see RayContext.h). Returns
/// the bit mask of the lanes entered and their entry distances (tOut is 32-byte aligned).
inline int intersectNode(const WideNode &n, const NodeRay &r, float tHigh, float tOut[kWidth]) {
#if MVCL_TRAVERSAL_AVX2
    const __m256 tx0 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(slabRow(n, r.c.nearRow[0])), r.ox), r.ix);
    const __m256 ty0 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(slabRow(n, r.c.nearRow[1])), r.oy), r.iy);
    const __m256 tz0 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(slabRow(n, r.c.nearRow[2])), r.oz), r.iz);
    const __m256 tx1 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(slabRow(n, r.c.farRow[0])), r.ox), r.fx);
    const __m256 ty1 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(slabRow(n, r.c.farRow[1])), r.oy), r.fy);
    const __m256 tz1 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(slabRow(n, r.c.farRow[2])), r.oz), r.fz);
    // vmaxps/vminps have the NaN rule of maxps/minps (second operand), as in the SSE path.
    __m256 tNear = _mm256_max_ps(tx0, r.tLow);
    tNear = _mm256_max_ps(ty0, tNear);
    tNear = _mm256_max_ps(tz0, tNear);
    // tHigh starts the far minimum (see intersectHalf).
    __m256 tFar = _mm256_min_ps(tx1, _mm256_set1_ps(tHigh));
    tFar = _mm256_min_ps(ty1, tFar);
    tFar = _mm256_min_ps(tz1, tFar);
    const __m256 ok = _mm256_cmp_ps(tNear, tFar, _CMP_LE_OQ);
    _mm256_store_ps(tOut, tNear);
    const __m256i lm =
        _mm256_and_si256(_mm256_load_si256(reinterpret_cast<const __m256i *>(n.layerMask)),
                         _mm256_set1_epi32(int(r.layerMask)));
    const int masked =
        _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(lm, _mm256_setzero_si256())));
    return _mm256_movemask_ps(ok) & ~masked;
#elif defined(__SSE2__)
    const __m128 high = _mm_set1_ps(tHigh);
    return intersectHalf(n, r, 0, high, tOut) | (intersectHalf(n, r, 4, high, tOut + 4) << 4);
#else
    const RayContext &c = r.c;
    int bits = 0;
    for (int lane = 0; lane < kWidth; ++lane) {
        if (!(n.layerMask[lane] & c.layerMask)) continue;
        const float b[6] = {n.bounds[0][lane], n.bounds[1][lane], n.bounds[2][lane],
                            n.bounds[3][lane], n.bounds[4][lane], n.bounds[5][lane]};
        if (intersectBox(b, c, tHigh, tOut[lane])) bits |= 1 << lane;
    }
    return bits;
#endif
}

/// Any-hit traversal. Any hit ends the query and tHigh never shrinks, so the children are not
/// ordered and the stack holds bare references: every pushed child already passed
/// tNear <= tHigh, so popping needs no distance test either.
inline bool occluded(const WideBvh &wide, const RayContext &c, float tHigh,
                     NearestHit &unused) {
    const WideNode *nodes = wide.nodes.get();
    const PrimBlock *blocks = wide.blocks.get();
    const PrimInfo *info = wide.info.get();
    const WatertightRay wray(c.ray);
    const WatertightRay4 wray4(wray);
    const NodeRay nodeRay(c);
    // Pairs are only taken while sp <= kStackSize - 2·kWidth, so above that mark the stack only
    // grows by the one-node steps, a plain depth-first descent: at most 7 entries per level
    // (kStackSize covers that for the whole depth) on top of the mark plus one pair's 16.
    uint32_t stack[2 * kStackSize + kWidth];
    int sp = 0;
    uint32_t cur = wide.root;
    for (;;) {
        if (WideLeaf::isLeaf(cur)) {
            if (testLeaf<true>(cur, blocks, info, c, wray4, unused)) return true;
        } else if (sp > 0 && sp <= kStackSize - 2 * kWidth && !WideLeaf::isLeaf(stack[sp - 1])) {
            // Two nodes at once. Traversal is bound by the latency of the chain node load →
            // slab test → child reference → next node load, not by throughput; any-hit does not
            // care about order, so the next pending node is tested alongside and the two
            // chains overlap.
            const uint32_t other = stack[--sp];
            alignas(32) float tNear[kWidth], tNearOther[kWidth];
            int bits = intersectNode(nodes[cur], nodeRay, tHigh, tNear);
            int bitsOther = intersectNode(nodes[other], nodeRay, tHigh, tNearOther);
            const uint32_t *child = nodes[other].child;
            for (; bitsOther; bitsOther &= bitsOther - 1) stack[sp++] = child[std::countr_zero(unsigned(bitsOther))];
            if (bits) {
                // The first child goes straight on, not through a stack store and reload.
                child = nodes[cur].child;
                cur = child[std::countr_zero(unsigned(bits))];
                for (bits &= bits - 1; bits; bits &= bits - 1) stack[sp++] = child[std::countr_zero(unsigned(bits))];
                continue;
            }
        } else {
            alignas(32) float tNear[kWidth];
            int bits = intersectNode(nodes[cur], nodeRay, tHigh, tNear);
            if (bits) {
                const uint32_t *child = nodes[cur].child;
                cur = child[std::countr_zero(unsigned(bits))];
                for (bits &= bits - 1; bits; bits &= bits - 1) stack[sp++] = child[std::countr_zero(unsigned(bits))];
                continue;
            }
        }
        if (sp == 0) return false;
        cur = stack[--sp];
    }
}

/// Any hit over the wide BVH: true on the first accepted hit (after the root box, occluded()).
inline bool anyHitWalk(const WideBvh &wide, const RayContext &c, NearestHit &unused) {
    if (wide.blockCount == 0) return false;
    const float tHigh = c.tMax * kTraversalSlackUp;
    float tEntry;
    if (!(wide.rootMask & c.layerMask) || !intersectBox(wide.rootBounds, c, tHigh, tEntry)) return false;
    return occluded(wide, c, tHigh, unused);
}

/// Closest hit over the planes [planes, planes + planeCount) and the wide BVH: offers candidates
/// to `best` (a NearestHit or a LayerPriorityHit) and returns whether it changed. Inlined into
/// the query entries below, which set up the query in the walk's instruction set.
template <class Best>
MVCL_KERNEL_INLINE bool closestWalk(const WideBvh &wide, const PlaneRecord *planes, std::size_t planeCount,
                                    const RayContext &c, Best &best) {
    // The planes first: a plane in front (the floor under a scene) caps the walk from its start,
    // and the cap only culls boxes beyond a hit that is already there (the result is a function
    // of the candidate set, not of their order).
    bool found = testPlanes<false>(planes, planeCount, c, best);
    if (wide.blockCount == 0 || !(wide.rootMask & c.layerMask)) return found;
    const WideNode *nodes = wide.nodes.get();
    const PrimBlock *blocks = wide.blocks.get();
    const PrimInfo *info = wide.info.get();
    float tHigh = std::min(c.tMax, best.cap()) * kTraversalSlackUp;
    const NodeRay nodeRay(c);

    struct Entry {
        uint32_t ref;
        float t;
    };
    // Sized as in occluded(): pairs are only taken below the same mark.
    Entry stack[2 * kStackSize + kWidth];
    int sp = 0;
    uint32_t cur = wide.root;
    // Sorted insertion of the entered lanes of a node into the run that starts at `base`.
    auto insert = [&](int base, int bits, const uint32_t *child, const float *tNear) {
        while (bits) {
            const int lane = std::countr_zero(unsigned(bits));
            bits &= bits - 1;
            const Entry e{child[lane], tNear[lane]};
            int j = sp++;
            while (j > base && stack[j - 1].t < e.t) {
                stack[j] = stack[j - 1];
                --j;
            }
            stack[j] = e;
        }
    };
    // The entered children (bits ≠ 0) of one node: the nearest becomes cur, the others wait on the
    // stack. One child (the common case deep in the tree) needs no stack at all. Otherwise the
    // children go straight onto the stack, kept in descending t by insertion (stable, so equal t
    // keep lane order), and the nearest is popped back: no scratch list to copy.
    auto descend = [&](int bits, const uint32_t *child, const float *tNear) {
        if (!(bits & (bits - 1))) {
            cur = child[std::countr_zero(unsigned(bits))];
            return;
        }
        const int rest = bits & (bits - 1);
        if (!(rest & (rest - 1))) {
            // Two children (the next most common case): the nearer goes on from a register, not
            // through a stack store and reload. Same order as insert(): on equal t the higher
            // lane comes first.
            const int l0 = std::countr_zero(unsigned(bits));
            const int l1 = std::countr_zero(unsigned(rest));
            const bool first0 = tNear[l0] < tNear[l1];
            stack[sp++] = first0 ? Entry{child[l1], tNear[l1]} : Entry{child[l0], tNear[l0]};
            cur = child[first0 ? l0 : l1];
            return;
        }
        insert(sp, bits, child, tNear);
        cur = stack[--sp].ref;
    };
    if (WideLeaf::isLeaf(cur)) {
        float tEntry;
        if (!intersectBox(wide.rootBounds, c, tHigh, tEntry)) return found;
    } else {
        // No test of the root's own box: it is the union of its children's, which the node test
        // below tests at once, as wide as one scalar box (a tree of one node, such as
        // cube-in-cube, then pays one box test per query, not two).
        alignas(32) float tNear[kWidth];
        const int bits = intersectNode(nodes[cur], nodeRay, tHigh, tNear);
        if (!bits) return found;
        descend(bits, nodes[cur].child, tNear);
    }
    // Only now: many rays miss every box, and the shear costs three divisions.
    const WatertightRay wray(c.ray);
    const WatertightRay4 wray4(wray);
    for (;;) {
        if (WideLeaf::isLeaf(cur)) {
            if (testLeaf<false>(cur, blocks, info, c, wray4, best)) {
                found = true;
                tHigh = std::min(c.tMax, best.cap()) * kTraversalSlackUp;
            }
        } else if (sp > 0 && sp <= kStackSize - 2 * kWidth && !WideLeaf::isLeaf(stack[sp - 1].ref) &&
                   stack[sp - 1].t <= tHigh) {
            // The next-nearest pending node is tested alongside (see occluded(): the node chain
            // is latency-bound). Both nodes' children go into one sorted run, so the visit order
            // stays nearest-first; the hit found does not depend on the order anyway.
            const uint32_t other = stack[--sp].ref;
            alignas(32) float tNear[kWidth], tNearOther[kWidth];
            const int bits = intersectNode(nodes[cur], nodeRay, tHigh, tNear);
            const int bitsOther = intersectNode(nodes[other], nodeRay, tHigh, tNearOther);
            // Where one of the two enters nothing, the other goes on as a single node would:
            // through descend()'s one- and two-child paths, not the insertion loops.
            if (bits && bitsOther) {
                const int base = sp;
                insert(base, bitsOther, nodes[other].child, tNearOther);
                insert(base, bits, nodes[cur].child, tNear);
                cur = stack[--sp].ref;
                continue;
            }
            if (bits | bitsOther) {
                if (bits) descend(bits, nodes[cur].child, tNear);
                else descend(bitsOther, nodes[other].child, tNearOther);
                continue;
            }
        } else {
            alignas(32) float tNear[kWidth];
            const int bits = intersectNode(nodes[cur], nodeRay, tHigh, tNear);
            if (bits) {
                descend(bits, nodes[cur].child, tNear);
                continue;
            }
        }
        // Pop the nearest pending subtree that can still hold a closer hit.
        for (;;) {
            if (sp == 0) return found;
            const Entry &e = stack[--sp];
            if (e.t <= tHigh) {
                cur = e.ref;
                break;
            }
        }
    }
}

/// SingleRayKernels::queryNearest: a whole closest-hit query of one layer.
inline bool queryNearest(const WideBvh &wide, const PlaneRecord *planes, std::size_t planeCount, const Ray &ray,
                         const RayQuery &query, float tMin, float tMax, Hit &hit) {
    const RayContext c(ray, query, tMin, tMax);
    NearestHit best;
    return closestWalk(wide, planes, planeCount, c, best) && best.resolve(hit);
}

/// SingleRayKernels::queryLayered: a whole closest-hit query with layer priority.
inline bool queryLayered(const WideBvh &wide, const PlaneRecord *planes, std::size_t planeCount, const Ray &ray,
                         const RayQuery &query, float tMin, float tMax, float contactWindow, Hit &hit) {
    const RayContext c(ray, query, tMin, tMax);
    LayerPriorityHit best(contactWindow);
    return closestWalk(wide, planes, planeCount, c, best) && best.resolve(hit);
}

} // namespace MVCL_ISA_NAMESPACE
} // namespace mvcl::detail
