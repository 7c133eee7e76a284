// Binned SAH BVH build (Wald 2007 style binning, up to 32 bins, all three axes in one pass),
// parallel over subtrees: every node of at least kMinParallelPrims pushes one child as a task of
// the framework's worker pool (a tbb::task_group in its arena), at any depth, so no large subtree
// is left to one thread at the end. Each node receives its bounds and centroid bounds from its
// parent (the partition pass computes them for both children), so a node reads its primitives
// twice: once to bin, once to partition. The tree depends only on the input, never on the
// thread count; only the slots of child pairs (taken from an atomic counter) do, and the wide
// collapse lays out its output independently of them.

#include "Bvh.h"
#include "TraversalIsa.h"
#include "core/WorkerArena_p.h"

#include <glm/common.hpp>

#include <mvcl/core/Error.h>
#include <mvcl/core/FloatBits.h>
#include <mvcl/core/WorkerPool.h>

#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <mutex>
#include <utility>
#include <vector>
#include <limits>
#include <new>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
// The AVX2 binning, SAH sweep and partition are compiled for their own functions only (#pragma
// GCC target below) and chosen at run time, as the AVX2 traversal is.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define MVCL_HAVE_AVX2_BINNING 1
#include <immintrin.h>
#else
#define MVCL_HAVE_AVX2_BINNING 0
#endif
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace mvcl::detail {

void AlignedFree::operator()(void *p) const { std::free(p); }

void *allocateAligned(std::size_t bytes) {
#if defined(__linux__)
    // Large arrays (build nodes, wide nodes, leaf blocks: megabytes written once, right after
    // allocation) on transparent huge pages where the system allows them on request: thousands
    // of 4 KiB first-touch faults were a visible share of the build.
    constexpr std::size_t kHuge = std::size_t(2) << 20;
    if (bytes >= 2 * kHuge) {
        const std::size_t size = (bytes + kHuge - 1) / kHuge * kHuge;
        void *p = std::aligned_alloc(kHuge, size);
        if (!p) throw std::bad_alloc();
        madvise(p, size, MADV_HUGEPAGE); // a hint: failure only means small pages
        return p;
    }
#endif
    void *p = std::aligned_alloc(64, std::max<std::size_t>(64, (bytes + 63) / 64 * 64));
    if (!p) throw std::bad_alloc();
    return p;
}

namespace {
constexpr int kBins = 32;
/// A subtree deeper than this is split at the object median: keeps the traversal stack bounded
/// for adversarial input (the stack holds at most depth entries).
constexpr int kMaxSahDepth = 64;
/// Below this many primitives a subtree is built on the calling thread (task overhead).
constexpr uint32_t kMinParallelPrims = 4096;
/// Nodes with at least this many primitives are binned on two threads (when building with more
/// than one): otherwise the root and its children are binned by one thread while others wait.
constexpr uint32_t kMinParallelBinning = 65536;
/// SAH cost of a node visit relative to one block (four primitives) of a leaf.
constexpr double kTraversalCost = 1.0;
/// Leaves are intersected four primitives at a time (PrimBlock): a leaf of 1..4 costs the same.
constexpr uint32_t kBlockSize = 4;

uint32_t blocksOf(uint32_t count) { return (count + kBlockSize - 1) / kBlockSize; }

/// 32 bytes, 16-aligned: lo and hi each load as 4 floats (the fourth lane is ignored).
struct alignas(16) BuildPrim {
    glm::vec3 lo;
    uint32_t id;
    glm::vec3 hi;
    uint32_t layerBit;
};
static_assert(sizeof(BuildPrim) == 32);

double halfArea(const glm::vec3 &lo, const glm::vec3 &hi) {
    const double dx = double(hi.x) - double(lo.x);
    const double dy = double(hi.y) - double(lo.y);
    const double dz = double(hi.z) - double(lo.z);
    return dx * dy + dy * dz + dz * dx;
}

struct NoInit {};

/// Bounds grown four lanes at a time (SSE when available); lane 3 is ignored.
struct Box4 {
#if defined(__SSE2__)
    __m128 lo, hi;
    Box4()
        : lo(_mm_set1_ps(std::numeric_limits<float>::infinity())),
          hi(_mm_set1_ps(-std::numeric_limits<float>::infinity())) {}
    /// Left for the caller to fill (bins: only the ones in use are reset).
    explicit Box4(NoInit) {}
    void grow(__m128 pLo, __m128 pHi) {
        lo = _mm_min_ps(lo, pLo);
        hi = _mm_max_ps(hi, pHi);
    }
    void grow(const Box4 &b) { grow(b.lo, b.hi); }
    void growPoint(__m128 p) { grow(p, p); }
    glm::vec3 min() const { return toVec3(lo); }
    glm::vec3 max() const { return toVec3(hi); }
    /// halfArea(min(), max()) with the extents taken in float (exact for all but huge boxes;
    /// the SAH only compares costs, and the same inputs always give the same result).
    double halfArea() const {
        alignas(16) float d[4];
        _mm_store_ps(d, _mm_sub_ps(hi, lo));
        return double(d[0]) * d[1] + double(d[1]) * d[2] + double(d[2]) * d[0];
    }
    static glm::vec3 toVec3(__m128 v) {
        alignas(16) float f[4];
        _mm_store_ps(f, v);
        return {f[0], f[1], f[2]};
    }
#else
    glm::vec3 lo, hi;
    Box4() : lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity()) {}
    explicit Box4(NoInit) {}
    void grow(const glm::vec3 &pLo, const glm::vec3 &pHi) {
        lo = glm::min(lo, pLo);
        hi = glm::max(hi, pHi);
    }
    void grow(const Box4 &b) { grow(b.lo, b.hi); }
    void growPoint(const glm::vec3 &p) { grow(p, p); }
    glm::vec3 min() const { return lo; }
    glm::vec3 max() const { return hi; }
    double halfArea() const {
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
    explicit PrimLanes(const BuildPrim &p)
        : lo(_mm_and_ps(_mm_load_ps(&p.lo.x), xyzMask())),
          hi(_mm_and_ps(_mm_load_ps(&p.hi.x), xyzMask())),
          c(_mm_add_ps(_mm_mul_ps(lo, _mm_set1_ps(0.5f)), _mm_mul_ps(hi, _mm_set1_ps(0.5f)))) {}
    static __m128 xyzMask() { return _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0)); }
    float centroid(int axis) const {
        alignas(16) float f[4];
        _mm_store_ps(f, c);
        return f[axis];
    }
};
#else
struct PrimLanes {
    glm::vec3 lo, hi, c;
    explicit PrimLanes(const BuildPrim &p) : lo(p.lo), hi(p.hi), c(0.5f * p.lo + 0.5f * p.hi) {}
    float centroid(int axis) const { return c[axis]; }
};
#endif

/// Geometry and centroid bounds of a primitive range.
struct RangeBounds {
    Box4 box;
    Box4 cbox;
    void grow(const PrimLanes &p) {
        box.grow(p.lo, p.hi);
        cbox.growPoint(p.c);
    }
};

RangeBounds boundsOf(const BuildPrim *prims, uint32_t begin, uint32_t end) {
    RangeBounds r;
    for (uint32_t i = begin; i < end; ++i) r.grow(PrimLanes(prims[i]));
    return r;
}

/// Maps centroids to bins on all three axes with the same float arithmetic as binOf() below
/// ((c − cmin) · scale, truncated, clamped), so binning and partitioning always agree.
struct Binner {
    glm::vec3 cmin;
    glm::vec3 scale;
    int nBins;

    int binOf(const BuildPrim &p, int axis) const {
        // The centroid lane of PrimLanes, computed with the same operations.
        const float c = p.lo[axis] * 0.5f + p.hi[axis] * 0.5f;
        const int b = int((c - cmin[axis]) * scale[axis]);
        return b < nBins - 1 ? b : nBins - 1; // ≥ 0 by construction (c ≥ cmin, scale ≥ 0)
    }
    void binsOf(const PrimLanes &p, int out[4]) const {
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

/// Per-axis bins of a primitive range: bounds and counts. Only the first nBins of each axis are
/// initialised: resetting all 3 × 32 dominated the cost of small nodes.
struct BinSet {
    struct Bin : Box4 {
        Bin() : Box4(NoInit{}) {}
    };
    Bin boxes[3][kBins];
    uint32_t counts[3][kBins];

    explicit BinSet(int nBins) {
        for (int axis = 0; axis < 3; ++axis)
            for (int b = 0; b < nBins; ++b) {
                static_cast<Box4 &>(boxes[axis][b]) = Box4{};
                counts[axis][b] = 0;
            }
    }

    void add(const Binner &binner, const BuildPrim *prims, uint32_t begin, uint32_t end) {
        for (uint32_t i = begin; i < end; ++i) {
            const PrimLanes p(prims[i]);
            alignas(16) int b[4];
            binner.binsOf(p, b);
            for (int axis = 0; axis < 3; ++axis) {
                boxes[axis][b[axis]].grow(p.lo, p.hi);
                ++counts[axis][b[axis]];
            }
        }
    }
    void merge(const BinSet &other, int nBins) {
        for (int axis = 0; axis < 3; ++axis)
            for (int b = 0; b < nBins; ++b) {
                boxes[axis][b].grow(other.boxes[axis][b]);
                counts[axis][b] += other.counts[axis][b];
            }
    }
};

#if MVCL_HAVE_AVX2_BINNING
#pragma GCC push_options
#pragma GCC target("avx2")
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

/// Builder::findSplit's binning and sweep on BinSet8, the three axes' sweeps side by side in
/// double lanes: the same costs, compared in findSplit's order (axis by axis, bin by bin), so
/// the same split (the tests build trees both ways and compare them).
void findSplitAvx2(const Binner &binner, const BuildPrim *prims, uint32_t begin, uint32_t end, bool halves,
                   int &bestAxis, int &bestSplit, double &bestCost) {
    const int nBins = binner.nBins;
    BinSet8 all(nBins);
    if (halves) {
        // As in findSplit: the halves as two isolated tasks, merged exactly.
        const uint32_t mid = begin + (end - begin) / 2;
        BinSet8 upper(nBins);
        tbb::this_task_arena::isolate([&] {
            tbb::parallel_invoke([&] { all.add(binner, prims, begin, mid); },
                                 [&] { upper.add(binner, prims, mid, end); });
        });
        all.merge(upper, nBins);
    } else {
        all.add(binner, prims, begin, end);
    }
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
        std::swap(prims[i], prims[j - 1]);
        grow(left, pj);
        grow(right, pi);
        ++i;
        --j;
    }
    leftOut = bounds(left);
    rightOut = bounds(right);
    return i;
}
#pragma GCC pop_options

/// Set by tests (forceSseBinning(), TraversalIsa.h) to run the SSE2 build passes on an AVX2 CPU.
std::atomic<bool> g_forceSseBinning{false};

/// Whether findSplit and the partition run their AVX2 variants (the CPU has AVX2 and no test
/// forces SSE2).
bool avx2Binning() {
    static const bool available = __builtin_cpu_supports("avx2");
    return available && !g_forceSseBinning.load(std::memory_order_relaxed);
}
#endif

/// Subtree builds are pushed as tasks whenever a node is large enough, at any depth, and idle
/// threads take them: with a fixed spawn depth a single large subtree below it kept one core busy
/// while the other waited at the end of the build. Tasks never wait for one another (results
/// that need both children are fixed up by finishLayerMasks() after the group is done), so there
/// are no joins inside the tree.
class Builder {
public:
    /// tasks: where subtrees are pushed (null: build everything on the calling thread). All
    /// calls then run inside the worker arena the group's tasks are spawned in.
    Builder(BuildPrim *prims, BvhNode *slots, int maxLeaf, tbb::task_group *tasks)
        : m_prims(prims), m_slots(slots), m_maxLeaf(maxLeaf), m_tasks(tasks) {}

    /// Builds the subtree of [begin, end) into `slot`; `bounds` are that range's bounds.
    void build(uint32_t slot, uint32_t begin, uint32_t end, int depth, const RangeBounds &bounds) {
        const glm::vec3 lo = bounds.box.min(), hi = bounds.box.max();
        const glm::vec3 clo = bounds.cbox.min(), chi = bounds.cbox.max();
        BvhNode &node = m_slots[slot];
        node.bounds[0] = lo.x, node.bounds[1] = lo.y, node.bounds[2] = lo.z;
        node.bounds[3] = hi.x, node.bounds[4] = hi.y, node.bounds[5] = hi.z;
        noteDepth(depth);

        const uint32_t n = end - begin;
        // A split costs the traversal step plus at least one block per side, more than the
        // single block of a leaf of up to four: such a node is a leaf whatever findSplit finds.
        if (n <= std::min<uint32_t>(uint32_t(m_maxLeaf), kBlockSize)) return makeLeaf(node, begin, n);

        // Fewer bins for small nodes: initialising 3 × 32 bins dominates the cost near the leaves.
        Binner binner{clo, glm::vec3(0.f), int(std::min<uint32_t>(kBins, std::max<uint32_t>(4, n)))};
        for (int axis = 0; axis < 3; ++axis) {
            const float extent = chi[axis] - clo[axis];
            // A flat axis (or an overflowing extent) bins everything into bin 0: no split there.
            // Tested before dividing, so that builds run clean with FP traps on.
            const float scale = extent > 0.f ? float(binner.nBins) * (1.f - 1.f / 4096.f) / extent : 0.f;
            binner.scale[axis] = std::isfinite(scale) ? scale : 0.f;
        }
        int bestAxis = -1, bestSplit = -1;
        double bestCost = std::numeric_limits<double>::infinity();
        if (depth < kMaxSahDepth) findSplit(binner, begin, end, bestAxis, bestSplit, bestCost);

        const double area = halfArea(lo, hi);
        const double splitCost =
            bestAxis >= 0 && area > 0.0 ? kTraversalCost + bestCost / area
                                        : std::numeric_limits<double>::infinity();
        if (n <= uint32_t(m_maxLeaf) && double(blocksOf(n)) <= splitCost)
            return makeLeaf(node, begin, n);

        uint32_t mid;
        RangeBounds left, right;
        if (bestAxis >= 0) {
#if MVCL_HAVE_AVX2_BINNING
            if (avx2Binning()) mid = partitionAvx2(binner, bestAxis, bestSplit, m_prims, begin, end, left, right);
            else
#endif
            mid = partition(binner, bestAxis, bestSplit, begin, end, left, right);
        } else {
            // No usable split (coincident centroids, or too deep): object median along the
            // widest centroid axis, ties by id so the result is deterministic.
            const glm::vec3 ce = chi - clo;
            const int axis = (ce.x >= ce.y && ce.x >= ce.z) ? 0 : (ce.y >= ce.z ? 1 : 2);
            mid = begin + n / 2;
            std::nth_element(m_prims + begin, m_prims + mid, m_prims + end,
                             [axis](const BuildPrim &a, const BuildPrim &b) {
                                 const float ca = PrimLanes(a).centroid(axis);
                                 const float cb = PrimLanes(b).centroid(axis);
                                 return ca != cb ? ca < cb : a.id < b.id;
                             });
            left = boundsOf(m_prims, begin, mid);
            right = boundsOf(m_prims, mid, end);
        }

        const uint32_t base = m_nextSlot.fetch_add(2, std::memory_order_relaxed);
        node.index = base; // interior: children at base, base + 1
        if (m_tasks && n >= kMinParallelPrims) {
            // Left as a task for any idle thread, right here. Neither waits for the other: the
            // layer mask of this node is filled in by finishLayerMasks() afterwards.
            m_tasks->run([this, base, begin, mid, depth, left] { build(base, begin, mid, depth + 1, left); });
            build(base + 1, mid, end, depth + 1, right);
            std::lock_guard<std::mutex> lock(m_spawnedMutex);
            m_spawned.push_back({depth, slot});
            return;
        }
        build(base, begin, mid, depth + 1, left);
        build(base + 1, mid, end, depth + 1, right);
        node.layerMask = m_slots[base].layerMask | m_slots[base + 1].layerMask;
    }

    /// Layer masks of the nodes that spawned a task, deepest first (their children are done).
    void finishLayerMasks() {
        std::sort(m_spawned.begin(), m_spawned.end(), std::greater<>());
        for (const auto &[depth, slot] : m_spawned) {
            BvhNode &node = m_slots[slot];
            node.layerMask = m_slots[node.offset()].layerMask | m_slots[node.offset() + 1].layerMask;
        }
    }

    int maxDepth() const { return m_maxDepth.load(); }
    std::size_t leafCount() const { return m_leafCount.load(); }
    uint32_t slotsUsed() const { return m_nextSlot.load(); }

private:
    /// One pass bins all three axes; then a sweep per axis evaluates every bin boundary with the
    /// leaf cost of each side counted in blocks.
    void findSplit(const Binner &binner, uint32_t begin, uint32_t end, int &bestAxis,
                   int &bestSplit, double &bestCost) const {
        const bool halves = m_tasks && end - begin >= kMinParallelBinning;
#if MVCL_HAVE_AVX2_BINNING
        if (avx2Binning()) return findSplitAvx2(binner, m_prims, begin, end, halves, bestAxis, bestSplit, bestCost);
#endif
        const int nBins = binner.nBins;
        BinSet all(nBins);
        if (halves) {
            // The top nodes would otherwise bin alone: bin the halves as two tasks, so an idle
            // thread can take one. Merging bins (min/max and integer counts) is exact, so the
            // result is the same whoever bins which half. Isolated: while the other half is
            // binned elsewhere, this thread waits instead of starting an unrelated subtree on top
            // of its stack, which would hold up this node's split (and its children) until that
            // whole subtree is done.
            const uint32_t mid = begin + (end - begin) / 2;
            BinSet upper(nBins);
            tbb::this_task_arena::isolate([&] {
                tbb::parallel_invoke([&] { all.add(binner, m_prims, begin, mid); },
                                     [&] { upper.add(binner, m_prims, mid, end); });
            });
            all.merge(upper, nBins);
        } else {
            all.add(binner, m_prims, begin, end);
        }
        const auto &bins = all.boxes;
        const auto &counts = all.counts;
        for (int axis = 0; axis < 3; ++axis) {
            if (binner.scale[axis] == 0.f) continue;
            const BinSet::Bin *axisBins = bins[axis];
            const uint32_t *axisCounts = counts[axis];
            double rightCost[kBins];
            Box4 acc;
            uint32_t count = 0;
            for (int b = nBins - 1; b > 0; --b) {
                acc.grow(axisBins[b]);
                count += axisCounts[b];
                rightCost[b] = count ? acc.halfArea() * blocksOf(count) : -1.0;
            }
            acc = Box4{};
            count = 0;
            for (int b = 0; b < nBins - 1; ++b) {
                acc.grow(axisBins[b]);
                count += axisCounts[b];
                if (count == 0 || rightCost[b + 1] < 0.0) continue;
                const double cost = acc.halfArea() * blocksOf(count) + rightCost[b + 1];
                if (cost < bestCost) bestCost = cost, bestAxis = axis, bestSplit = b;
            }
        }
    }

    /// In-place partition by bin (≤ split goes left), computing both sides' bounds on the way.
    /// Sequential and deterministic.
    uint32_t partition(const Binner &binner, int axis, int split, uint32_t begin, uint32_t end,
                       RangeBounds &left, RangeBounds &right) {
        uint32_t i = begin, j = end;
        for (;;) {
            while (i < j && binner.binOf(m_prims[i], axis) <= split) {
                left.grow(PrimLanes(m_prims[i]));
                ++i;
            }
            while (i < j && binner.binOf(m_prims[j - 1], axis) > split) {
                right.grow(PrimLanes(m_prims[j - 1]));
                --j;
            }
            if (i == j) return i;
            // prims[i] belongs right, prims[j − 1] left.
            std::swap(m_prims[i], m_prims[j - 1]);
            left.grow(PrimLanes(m_prims[i]));
            right.grow(PrimLanes(m_prims[j - 1]));
            ++i;
            --j;
        }
    }

    void makeLeaf(BvhNode &node, uint32_t begin, uint32_t n) {
        node.index = (n << BvhNode::kCountShift) | begin;
        uint32_t mask = 0;
        for (uint32_t i = begin; i < begin + n; ++i) mask |= m_prims[i].layerBit;
        node.layerMask = mask;
        m_leafCount.fetch_add(1, std::memory_order_relaxed);
    }

    void noteDepth(int depth) {
        int cur = m_maxDepth.load(std::memory_order_relaxed);
        while (depth > cur && !m_maxDepth.compare_exchange_weak(cur, depth)) {
        }
    }

    BuildPrim *m_prims;
    BvhNode *m_slots;
    int m_maxLeaf;
    tbb::task_group *m_tasks;
    std::mutex m_spawnedMutex;
    std::vector<std::pair<int, uint32_t>> m_spawned; ///< (depth, slot) of nodes that spawned
    std::atomic<uint32_t> m_nextSlot{1}; ///< slot 0 is the root
    std::atomic<int> m_maxDepth{0};
    std::atomic<std::size_t> m_leafCount{0};
};

std::unique_ptr<BvhNode[], AlignedFree> allocateNodes(std::size_t count) {
    return std::unique_ptr<BvhNode[], AlignedFree>(
        static_cast<BvhNode *>(allocateAligned(count * sizeof(BvhNode))));
}

} // namespace

void forceSseBinning(bool force) {
#if MVCL_HAVE_AVX2_BINNING
    g_forceSseBinning.store(force);
#else
    (void)force;
#endif
}

Bvh buildBvh(BvhBuildInput input) {
    Bvh bvh;
    const std::size_t n = input.prims.size();
    if (n == 0) return bvh;
    if (n >= (std::size_t(1) << (BvhNode::kCountShift - 1)))
        throw Error("tracer", "too many primitives for the BVH (" + std::to_string(n) + ")");

    // Boxes in parallel chunks; the root bounds are merged from per-chunk bounds (min/max is
    // exact in any order).
    // Not value-initialised: the chunks below write every record.
    const std::unique_ptr<BuildPrim[], AlignedFree> build(
        static_cast<BuildPrim *>(allocateAligned(n * sizeof(BuildPrim))));
    constexpr std::size_t kChunk = 16384;
    const std::size_t chunks = (n + kChunk - 1) / kChunk;
    std::vector<RangeBounds> chunkBounds(chunks);
    mvcl::parallelFor(chunks, input.threads, [&](std::size_t c) {
        const std::size_t end = std::min(n, (c + 1) * kChunk);
        RangeBounds bounds; // local: neighbouring chunks' bounds share cache lines
        for (std::size_t i = c * kChunk; i < end; ++i) {
            const PrimRecord &r = input.prims[i];
            BuildPrim &b = build[i];
            if (r.kind == uint8_t(PrimKind::Sphere)) {
                const glm::vec3 rad(r.p1.x);
                b.lo = r.p0 - rad;
                b.hi = r.p0 + rad;
                // Round outward: c ± r is rounded to nearest and could cut the sphere by an ulp.
                for (int k = 0; k < 3; ++k) {
                    b.lo[k] = nextFloatDown(b.lo[k]);
                    b.hi[k] = nextFloatUp(b.hi[k]);
                }
            } else {
                b.lo = glm::min(r.p0, glm::min(r.p1, r.p2));
                b.hi = glm::max(r.p0, glm::max(r.p1, r.p2));
            }
            b.id = uint32_t(i);
            b.layerBit = 1u << r.layer;
            bounds.grow(PrimLanes(b));
        }
        chunkBounds[c] = bounds;
    });
    RangeBounds rootBounds;
    for (const RangeBounds &cb : chunkBounds) {
        rootBounds.box.grow(cb.box);
        rootBounds.cbox.grow(cb.cbox);
    }

    const int maxLeaf = std::clamp(input.maxLeafSize, 1, int(BvhNode::kMaxLeafCount));
    // At most n leaves, so at most 2n − 1 nodes; pages past the ones used are never touched.
    bvh.nodes = allocateNodes(2 * n);
    const auto keepStats = [&bvh](const Builder &builder) {
        bvh.nodeCount = builder.slotsUsed();
        bvh.leafCount = builder.leafCount();
        bvh.maxDepth = builder.maxDepth();
    };
    if (input.threads > 1) {
        // The group is made and waited for inside the arena: run() spawns into the arena of the
        // calling thread, and wait() belongs in the same one.
        workerArena(input.threads).execute([&] {
            tbb::task_group tasks;
            Builder builder(build.get(), bvh.nodes.get(), maxLeaf, &tasks);
            tasks.run_and_wait([&] { builder.build(0, 0, uint32_t(n), 0, rootBounds); });
            builder.finishLayerMasks();
            keepStats(builder);
        });
    } else {
        Builder builder(build.get(), bvh.nodes.get(), maxLeaf, nullptr);
        builder.build(0, 0, uint32_t(n), 0, rootBounds);
        keepStats(builder);
    }

    bvh.order.resize(n);
    for (std::size_t i = 0; i < n; ++i) bvh.order[i] = build[i].id;
    bvh.prims = std::move(input.prims);
    return bvh;
}

} // namespace mvcl::detail
