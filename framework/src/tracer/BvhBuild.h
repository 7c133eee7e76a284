#pragma once
// Private: the records and bounds of the binned SAH build (BvhBuilder.cpp), which the AVX2
// binning and partition (BvhBuildAvx2.cpp, a unit compiled with -mavx2) take and return through
// their table (KernelTables.h). One type for every instruction set: their member functions are
// MVCL_KERNEL_INLINE, never an out-of-line copy one unit could take from another (KernelIsa.h).

#include "Bvh.h"
#include "KernelIsa.h"

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mvcl::detail {

/// Bins per axis, at most (small nodes use fewer).
inline constexpr int kBins = 32;
/// Leaves are intersected four primitives at a time (PrimBlock): a leaf of 1..4 costs the same.
inline constexpr uint32_t kBlockSize = 4;

/// Room for the bins of one primitive range in the layout of the AVX2 binning (BvhBuildAvx2.cpp),
/// which the code that holds it never looks into: the threads that bin a node's two halves are
/// the build's business (BvhBuilder.cpp), the bins that of the instruction set's unit.
struct alignas(64) BinStorage {
    unsigned char bytes[4096];
};

/// 32 bytes, 16-aligned: lo and hi each load as 4 floats (the fourth lane is ignored).
struct alignas(16) BuildPrim {
    glm::vec3 lo;
    uint32_t id;
    glm::vec3 hi;
    uint32_t layerBit;
};
static_assert(sizeof(BuildPrim) == 32);

struct NoInit {};

/// Bounds grown four lanes at a time (SSE when available); lane 3 is ignored.
struct Box4 {
#if defined(__SSE2__)
    __m128 lo, hi;
    MVCL_KERNEL_INLINE Box4()
        : lo(_mm_set1_ps(std::numeric_limits<float>::infinity())),
          hi(_mm_set1_ps(-std::numeric_limits<float>::infinity())) {}
    /// Left for the caller to fill (bins: only the ones in use are reset).
    MVCL_KERNEL_INLINE explicit Box4(NoInit) {}
    MVCL_KERNEL_INLINE void grow(__m128 pLo, __m128 pHi) {
        lo = _mm_min_ps(lo, pLo);
        hi = _mm_max_ps(hi, pHi);
    }
    MVCL_KERNEL_INLINE void grow(const Box4 &b) { grow(b.lo, b.hi); }
    MVCL_KERNEL_INLINE void growPoint(__m128 p) { grow(p, p); }
    MVCL_KERNEL_INLINE glm::vec3 min() const { return toVec3(lo); }
    MVCL_KERNEL_INLINE glm::vec3 max() const { return toVec3(hi); }
    /// halfArea(min(), max()) with the extents taken in float (exact for all but huge boxes;
    /// the SAH only compares costs, and the same inputs always give the same result).
    MVCL_KERNEL_INLINE double halfArea() const {
        alignas(16) float d[4];
        _mm_store_ps(d, _mm_sub_ps(hi, lo));
        return double(d[0]) * d[1] + double(d[1]) * d[2] + double(d[2]) * d[0];
    }
    MVCL_KERNEL_INLINE static glm::vec3 toVec3(__m128 v) {
        alignas(16) float f[4];
        _mm_store_ps(f, v);
        return {f[0], f[1], f[2]};
    }
#else
    glm::vec3 lo, hi;
    MVCL_KERNEL_INLINE Box4()
        : lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity()) {}
    MVCL_KERNEL_INLINE explicit Box4(NoInit) {}
    MVCL_KERNEL_INLINE void grow(const glm::vec3 &pLo, const glm::vec3 &pHi) {
        lo = glm::min(lo, pLo);
        hi = glm::max(hi, pHi);
    }
    MVCL_KERNEL_INLINE void grow(const Box4 &b) { grow(b.lo, b.hi); }
    MVCL_KERNEL_INLINE void growPoint(const glm::vec3 &p) { grow(p, p); }
    MVCL_KERNEL_INLINE glm::vec3 min() const { return lo; }
    MVCL_KERNEL_INLINE glm::vec3 max() const { return hi; }
    MVCL_KERNEL_INLINE double halfArea() const {
        const glm::vec3 d = hi - lo;
        return double(d[0]) * d[1] + double(d[1]) * d[2] + double(d[2]) * d[0];
    }
#endif
};

/// The loads of one primitive: its box and its centroid (lo/2 + hi/2, which cannot overflow for
/// huge coordinates).
#if defined(__SSE2__)
struct PrimLanes {
    __m128 lo, hi, c;
    // The fourth lane (id, layer bit) is cleared: as a float it is a denormal, slow to multiply.
    MVCL_KERNEL_INLINE explicit PrimLanes(const BuildPrim &p)
        : lo(_mm_and_ps(_mm_load_ps(&p.lo.x), xyzMask())),
          hi(_mm_and_ps(_mm_load_ps(&p.hi.x), xyzMask())),
          c(_mm_add_ps(_mm_mul_ps(lo, _mm_set1_ps(0.5f)), _mm_mul_ps(hi, _mm_set1_ps(0.5f)))) {}
    MVCL_KERNEL_INLINE static __m128 xyzMask() { return _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0)); }
    MVCL_KERNEL_INLINE float centroid(int axis) const {
        alignas(16) float f[4];
        _mm_store_ps(f, c);
        return f[axis];
    }
};
#else
struct PrimLanes {
    glm::vec3 lo, hi, c;
    MVCL_KERNEL_INLINE explicit PrimLanes(const BuildPrim &p) : lo(p.lo), hi(p.hi), c(0.5f * p.lo + 0.5f * p.hi) {}
    MVCL_KERNEL_INLINE float centroid(int axis) const { return c[axis]; }
};
#endif

/// Geometry and centroid bounds of a primitive range.
struct RangeBounds {
    Box4 box;
    Box4 cbox;
    MVCL_KERNEL_INLINE void grow(const PrimLanes &p) {
        box.grow(p.lo, p.hi);
        cbox.growPoint(p.c);
    }
};

/// Maps centroids to bins on all three axes with the same float arithmetic as binOf() below
/// ((c − cmin) · scale, truncated, clamped), so binning and partitioning always agree.
struct Binner {
    glm::vec3 cmin;
    glm::vec3 scale;
    int nBins;

    MVCL_KERNEL_INLINE int binOf(const BuildPrim &p, int axis) const {
        // The centroid lane of PrimLanes, computed with the same operations.
        const float c = p.lo[axis] * 0.5f + p.hi[axis] * 0.5f;
        const int b = int((c - cmin[axis]) * scale[axis]);
        return b < nBins - 1 ? b : nBins - 1; // ≥ 0 by construction (c ≥ cmin, scale ≥ 0)
    }
    MVCL_KERNEL_INLINE void binsOf(const PrimLanes &p, int out[4]) const {
#if defined(__SSE2__)
        const __m128 rel = _mm_sub_ps(p.c, _mm_setr_ps(cmin.x, cmin.y, cmin.z, 0.f));
        const __m128i b = _mm_cvttps_epi32(_mm_mul_ps(rel, _mm_setr_ps(scale.x, scale.y, scale.z, 0.f)));
        // min(b, nBins − 1) with SSE2 compares (pminsd is SSE4.1).
        const __m128i last = _mm_set1_epi32(nBins - 1);
        const __m128i over = _mm_cmpgt_epi32(b, last);
        __m128i clamped = _mm_or_si128(_mm_and_si128(over, last), _mm_andnot_si128(over, b));
        // max(b, 0): on an axis whose extent overflows (coordinates near ±3.4e38) scale is 0 but
        // c − cmin can be ∞, and ∞·0 = NaN converts to INT_MIN: without this, a negative bin
        // index (catalogue case 13, garbage geometry, crashed here). Such an axis is never split.
        clamped = _mm_andnot_si128(_mm_cmpgt_epi32(_mm_setzero_si128(), clamped), clamped);
        _mm_storeu_si128(reinterpret_cast<__m128i *>(out), clamped);
#else
        for (int axis = 0; axis < 3; ++axis) {
            const float f = (p.c[axis] - cmin[axis]) * scale[axis];
            const int b = f >= 1.f ? int(f) : 0; // NaN (∞·0 on an overflowing axis) → bin 0
            out[axis] = b < nBins - 1 ? b : nBins - 1;
        }
#endif
    }
};

/// The build records of `prims` (their boxes, ids and layer bits, in the same order) and the
/// bounds of them all: the first pass of both builders. Throws mvcl::Error("tracer", ...) for
/// more primitives than a leaf's index can address.
struct BuildPrims {
    std::unique_ptr<BuildPrim[], AlignedFree> prims;
    RangeBounds bounds;
};
BuildPrims makeBuildPrims(const PrimArray &prims, int threads, Pages pages);

} // namespace mvcl::detail
