// The BVH build's binning, SAH sweep and partition with AVX2, the passes that dominate the build
// (BvhBuilder.cpp has their SSE2 form, Builder::findSplit and Builder::partition, and both build
// the same tree bit for bit). framework/CMakeLists.txt compiles this file with -mavx2; nothing
// here runs unless KernelDispatch.cpp found AVX2 on the CPU, and every function it compiles is in
// namespace isa_avx2 (KernelIsa.h).

#define MVCL_ISA_NAMESPACE isa_avx2

#include "KernelTables.h"

#if defined(__AVX2__) && MVCL_EXTENSION_KERNELS

#include "BvhBuild.h"

#include <cstdint>
#include <limits>
#include <new>
#include <type_traits>
#include <utility>

#include <immintrin.h>

namespace mvcl::detail {
inline namespace MVCL_ISA_NAMESPACE {

/// BinSet with AVX2, for the binning pass that dominates the build (half of findSplit's
/// instructions, 63 per primitive with SSE2). A bin is one 256-bit register holding
/// [min x, y, z, 0 | −max x, y, z, −0], so growing it by a primitive is a single vminps of the
/// primitive's 32-byte record with its upper half negated (max(a, b) = −min(−a, −b), exact, and
/// with the operand order of Box4::grow a NaN lane takes the primitive's value in both forms).
/// The bin indices are Binner::binsOf()'s: the same float operations on the same masked lanes,
/// the clamps with pminsd/pmaxsd.
struct BinSet8 {
    __m256 boxes[3][kBins];
    /// [bin][axis], axis 3 unused: the sweep loads the three axes' counts of a bin at once.
    alignas(16) uint32_t counts[kBins][4];

    explicit BinSet8(int nBins) {
        for (int b = 0; b < nBins; ++b) {
            for (int axis = 0; axis < 3; ++axis) boxes[axis][b] = _mm256_set1_ps(std::numeric_limits<float>::infinity());
            _mm_store_si128(reinterpret_cast<__m128i *>(counts[b]), _mm_setzero_si128());
        }
    }

    void add(const Binner &binner, const BuildPrim *prims, uint32_t begin, uint32_t end) {
        // Lanes 3 and 7 (id, layer bit) cleared as in PrimLanes: as floats they may be denormals.
        const __m256 xyz = _mm256_castsi256_ps(_mm256_setr_epi32(-1, -1, -1, 0, -1, -1, -1, 0));
        const __m256 negateUpper = _mm256_castsi256_ps(_mm256_setr_epi32(
            0, 0, 0, 0, int(0x80000000u), int(0x80000000u), int(0x80000000u), int(0x80000000u)));
        const __m128 half = _mm_set1_ps(0.5f);
        const __m128 cmin = _mm_setr_ps(binner.cmin.x, binner.cmin.y, binner.cmin.z, 0.f);
        const __m128 scale = _mm_setr_ps(binner.scale.x, binner.scale.y, binner.scale.z, 0.f);
        const __m128i last = _mm_set1_epi32(binner.nBins - 1);
        const __m128i zero = _mm_setzero_si128();
        for (uint32_t i = begin; i < end; ++i) {
            const __m256 p = _mm256_and_ps(_mm256_loadu_ps(&prims[i].lo.x), xyz);
            const __m128 lo = _mm256_castps256_ps128(p), hi = _mm256_extractf128_ps(p, 1);
            // PrimLanes::c and Binner::binsOf, operation for operation.
            const __m128 c = _mm_add_ps(_mm_mul_ps(lo, half), _mm_mul_ps(hi, half));
            const __m128i raw = _mm_cvttps_epi32(_mm_mul_ps(_mm_sub_ps(c, cmin), scale));
            const __m128i b = _mm_max_epi32(_mm_min_epi32(raw, last), zero);
            const __m256 q = _mm256_xor_ps(p, negateUpper);
            const int bx = _mm_cvtsi128_si32(b), by = _mm_extract_epi32(b, 1), bz = _mm_extract_epi32(b, 2);
            boxes[0][bx] = _mm256_min_ps(boxes[0][bx], q);
            boxes[1][by] = _mm256_min_ps(boxes[1][by], q);
            boxes[2][bz] = _mm256_min_ps(boxes[2][bz], q);
            ++counts[bx][0];
            ++counts[by][1];
            ++counts[bz][2];
        }
    }
    void merge(const BinSet8 &other, int nBins) {
        for (int b = 0; b < nBins; ++b) {
            for (int axis = 0; axis < 3; ++axis)
                boxes[axis][b] = _mm256_min_ps(boxes[axis][b], other.boxes[axis][b]);
            const __m128i *o = reinterpret_cast<const __m128i *>(other.counts[b]);
            __m128i *c = reinterpret_cast<__m128i *>(counts[b]);
            _mm_store_si128(c, _mm_add_epi32(_mm_load_si128(c), _mm_load_si128(o)));
        }
    }
};

/// The SAH terms of the three axes' accumulated boxes at once, one axis per double lane:
/// Box4::halfArea() · blocksOf(count), with count 0 giving −1 (no box). In BinSet8's form
/// lo + (−hi) = −(hi − lo) exactly (rounding to nearest is symmetric) and the products of two
/// negated extents are those of the extents, so each lane is the double value Box4 computes,
/// operation for operation: (dx·dy + dy·dz) + dz·dx, then the product with the block count.
inline __m256d sahTerms(const __m256 acc[3], __m128i count) {
    __m128 e0 = _mm_add_ps(_mm256_castps256_ps128(acc[0]), _mm256_extractf128_ps(acc[0], 1));
    __m128 e1 = _mm_add_ps(_mm256_castps256_ps128(acc[1]), _mm256_extractf128_ps(acc[1], 1));
    __m128 e2 = _mm_add_ps(_mm256_castps256_ps128(acc[2]), _mm256_extractf128_ps(acc[2], 1));
    __m128 e3 = _mm_setzero_ps();
    _MM_TRANSPOSE4_PS(e0, e1, e2, e3); // e0: the x extents of axes 0, 1, 2; e1: y; e2: z
    const __m256d dx = _mm256_cvtps_pd(e0), dy = _mm256_cvtps_pd(e1), dz = _mm256_cvtps_pd(e2);
    const __m256d area = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dy), _mm256_mul_pd(dy, dz)), _mm256_mul_pd(dz, dx));
    const __m128i blocks = _mm_srli_epi32(_mm_add_epi32(count, _mm_set1_epi32(int(kBlockSize) - 1)), 2);
    static_assert(kBlockSize == 4, "blocks = (count + 3) >> 2");
    const __m256d none = _mm256_castsi256_pd(_mm256_cvtepi32_epi64(_mm_cmpeq_epi32(count, _mm_setzero_si128())));
    return _mm256_blendv_pd(_mm256_mul_pd(area, _mm256_cvtepi32_pd(blocks)), _mm256_set1_pd(-1.0), none);
}

/// The bins of [begin, end) as BinSet8, made in the caller's storage (BvhBuild.h, BinStorage):
/// one half of a node binned as two tasks.
void binAvx2(const Binner &binner, const BuildPrim *prims, uint32_t begin, uint32_t end, BinStorage &out) {
    static_assert(sizeof(BinSet8) <= sizeof(BinStorage) && alignof(BinSet8) <= alignof(BinStorage));
    static_assert(std::is_trivially_destructible_v<BinSet8>);
    (new (out.bytes) BinSet8(binner.nBins))->add(binner, prims, begin, end);
}

inline const BinSet8 &binsIn(const BinStorage &storage) {
    return *std::launder(reinterpret_cast<const BinSet8 *>(storage.bytes));
}

/// Adds `other`'s bins to `all`'s (exact: min and integer sums).
void mergeBinsAvx2(BinStorage &all, const BinStorage &other, int nBins) {
    std::launder(reinterpret_cast<BinSet8 *>(all.bytes))->merge(binsIn(other), nBins);
}

/// Builder::findSplit's sweep on BinSet8, the three axes' sweeps side by side in double lanes:
/// the same costs, compared in findSplit's order (axis by axis, bin by bin), so the same split
/// (the tests build trees both ways and compare them).
inline void sweep(const Binner &binner, const BinSet8 &all, int &bestAxis, int &bestSplit, double &bestCost) {
    const int nBins = binner.nBins;
    const __m256 empty = _mm256_set1_ps(std::numeric_limits<float>::infinity());
    alignas(32) double rightCost[kBins][4];
    __m256 acc[3] = {empty, empty, empty};
    __m128i count = _mm_setzero_si128();
    for (int b = nBins - 1; b > 0; --b) {
        for (int axis = 0; axis < 3; ++axis) acc[axis] = _mm256_min_ps(acc[axis], all.boxes[axis][b]);
        count = _mm_add_epi32(count, _mm_load_si128(reinterpret_cast<const __m128i *>(all.counts[b])));
        _mm256_store_pd(rightCost[b], sahTerms(acc, count));
    }
    // cost[b]: left side up to bin b plus right side from b + 1; NaN where findSplit skips
    // (no primitive on either side), which never compares below bestCost.
    alignas(32) double cost[kBins][4];
    acc[0] = acc[1] = acc[2] = empty;
    count = _mm_setzero_si128();
    const __m256d zero = _mm256_setzero_pd();
    const __m256d nan = _mm256_set1_pd(std::numeric_limits<double>::quiet_NaN());
    for (int b = 0; b < nBins - 1; ++b) {
        for (int axis = 0; axis < 3; ++axis) acc[axis] = _mm256_min_ps(acc[axis], all.boxes[axis][b]);
        count = _mm_add_epi32(count, _mm_load_si128(reinterpret_cast<const __m128i *>(all.counts[b])));
        const __m256d left = sahTerms(acc, count), right = _mm256_load_pd(rightCost[b + 1]);
        const __m256d skip = _mm256_or_pd(_mm256_cmp_pd(left, zero, _CMP_LT_OQ), _mm256_cmp_pd(right, zero, _CMP_LT_OQ));
        _mm256_store_pd(cost[b], _mm256_blendv_pd(_mm256_add_pd(left, right), nan, skip));
    }
    for (int axis = 0; axis < 3; ++axis) {
        if (binner.scale[axis] == 0.f) continue;
        for (int b = 0; b < nBins - 1; ++b)
            if (cost[b][axis] < bestCost) bestCost = cost[b][axis], bestAxis = axis, bestSplit = b;
    }
}

/// sweep() on the bins of the caller's storage (a node binned as two halves, merged).
void sweepAvx2(const Binner &binner, const BinStorage &bins, int &bestAxis, int &bestSplit, double &bestCost) {
    sweep(binner, binsIn(bins), bestAxis, bestSplit, bestCost);
}

/// Binning and sweep of a node binned on one thread (all but the largest nodes). The bins are a
/// local here, not the caller's storage: __m256 may alias anything, and only for a local does
/// the compiler know that storing a bin does not change the primitives being read (binning into
/// BinStorage made single-threaded builds 6 % slower).
void findSplitAvx2(const Binner &binner, const BuildPrim *prims, uint32_t begin, uint32_t end, int &bestAxis,
                   int &bestSplit, double &bestCost) {
    BinSet8 all(binner.nBins);
    all.add(binner, prims, begin, end);
    sweep(binner, all, bestAxis, bestSplit, bestCost);
}

/// Builder::partition with AVX2: the same swaps in the same order (each primitive's side is
/// Binner::binOf's, from the same float operations on its centroid lane), and both sides' bounds
/// grown as RangeBounds::grow does, with the primitive's loads and centroid shared between the
/// side test and the bounds.
uint32_t partitionAvx2(const Binner &binner, int axis, int split, BuildPrim *prims, uint32_t begin, uint32_t end,
                       RangeBounds &leftOut, RangeBounds &rightOut) {
    const __m256 xyz = _mm256_castsi256_ps(_mm256_setr_epi32(-1, -1, -1, 0, -1, -1, -1, 0));
    const __m256 negateUpper = _mm256_castsi256_ps(_mm256_setr_epi32(
        0, 0, 0, 0, int(0x80000000u), int(0x80000000u), int(0x80000000u), int(0x80000000u)));
    const __m128 half = _mm_set1_ps(0.5f);
    const __m128 cmin = _mm_set1_ps(binner.cmin[axis]), scale = _mm_set1_ps(binner.scale[axis]);
    const int last = binner.nBins - 1;
    // binOf: c = lo·½ + hi·½, int((c − cmin)·scale), at most the last bin; the centroid of all
    // three axes as PrimLanes computes it, then the one lane of `axis`.
    struct Prim {
        __m256 q, c;
        int bin;
    };
    auto load = [&](const BuildPrim &bp) {
        const __m256 p = _mm256_and_ps(_mm256_loadu_ps(&bp.lo.x), xyz);
        const __m128 c = _mm_add_ps(_mm_mul_ps(_mm256_castps256_ps128(p), half),
                                    _mm_mul_ps(_mm256_extractf128_ps(p, 1), half));
        alignas(16) float cs[4];
        _mm_store_ps(cs, c);
        const int b = _mm_cvtt_ss2si(_mm_mul_ss(_mm_sub_ss(_mm_set_ss(cs[axis]), cmin), scale));
        return Prim{_mm256_xor_ps(p, negateUpper), _mm256_xor_ps(_mm256_set_m128(c, c), negateUpper),
                    b < last ? b : last};
    };
    // Both sides' geometry and centroid bounds in BinSet8's form ([min | −max], one vminps to
    // grow each), handed back as RangeBounds at the end (exact: min, max and negation).
    const __m256 empty = _mm256_set1_ps(std::numeric_limits<float>::infinity());
    __m256 left[2] = {empty, empty}, right[2] = {empty, empty};
    auto grow = [](__m256 r[2], const Prim &p) {
        r[0] = _mm256_min_ps(r[0], p.q);
        r[1] = _mm256_min_ps(r[1], p.c);
    };
    auto bounds = [](const __m256 r[2]) {
        const __m128 sign = _mm_castsi128_ps(_mm_set1_epi32(int(0x80000000u)));
        RangeBounds out;
        out.box.grow(_mm256_castps256_ps128(r[0]), _mm_xor_ps(_mm256_extractf128_ps(r[0], 1), sign));
        out.cbox.grow(_mm256_castps256_ps128(r[1]), _mm_xor_ps(_mm256_extractf128_ps(r[1], 1), sign));
        return out;
    };
    uint32_t i = begin, j = end;
    for (;;) {
        Prim pi{}, pj{};
        while (i < j && (pi = load(prims[i])).bin <= split) {
            grow(left, pi);
            ++i;
        }
        while (i < j && (pj = load(prims[j - 1])).bin > split) {
            grow(right, pj);
            --j;
        }
        if (i == j) break;
        // prims[i] belongs right, prims[j − 1] left.
        // By hand rather than std::swap, a library template the baseline code instantiates too
        // (KernelIsa.h).
        const BuildPrim moved = prims[i];
        prims[i] = prims[j - 1];
        prims[j - 1] = moved;
        grow(left, pj);
        grow(right, pi);
        ++i;
        --j;
    }
    leftOut = bounds(left);
    rightOut = bounds(right);
    return i;
}

} // namespace MVCL_ISA_NAMESPACE

namespace {
constinit const BuildKernels kTable{findSplitAvx2, binAvx2, mergeBinsAvx2, sweepAvx2, partitionAvx2};
} // namespace

constinit const BuildKernels *const kBuildKernelsAvx2 = &kTable;

} // namespace mvcl::detail

#elif defined(__x86_64__) && MVCL_EXTENSION_KERNELS
#error "framework/CMakeLists.txt compiles this unit with -mavx2 on x86-64"
#else // not built for AVX2 (not an x86-64 target, or not optimised for speed): the SSE2 passes of BvhBuilder.cpp

namespace mvcl::detail {
constinit const BuildKernels *const kBuildKernelsAvx2 = nullptr;
} // namespace mvcl::detail

#endif
