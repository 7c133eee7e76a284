// The quick BVH build (BvhQuality::Quick): primitives sorted along a Morton curve of their
// centroids, and the tree read off the sorted codes, each node split where the highest bit that
// differs across its range changes (a linear BVH). No surface areas are compared and no
// primitive is moved after the sort, so it builds several times faster than the binned SAH
// build and traces slower: a first image of a large model while the full build runs.
//
// Deterministic like the SAH build: the sort is stable (equal codes keep the input order), so the
// tree depends only on the input; only the slots of child pairs depend on the thread count.

#include "Bvh.h"
#include "BvhBuild.h"
#include "core/WorkerArena_p.h"

#include <mvcl/core/WorkerPool.h>

#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <memory>
#include <cmath>
#include <utility>
#include <vector>

namespace mvcl::detail {

namespace {

/// Bits per axis of a Morton code: a 1024³ grid over the centroids' bounds. Primitives sharing a
/// cell share a code and are split at their median (in input order).
constexpr int kBitsPerAxis = 10;
/// Below this many primitives a subtree is built on the calling thread (task overhead).
constexpr uint32_t kMinParallelPrims = 4096;

/// The bits of v (10 of them) spread to every third bit.
uint32_t spreadBits(uint32_t v) {
    v = (v | (v << 16)) & 0x030000FFu;
    v = (v | (v << 8)) & 0x0300F00Fu;
    v = (v | (v << 4)) & 0x030C30C3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

/// Sorts (code << 32 | id) keys by their codes, stably: least significant digit first, one pass
/// per 10-bit digit of the 30-bit code.
/// Keys are not value-initialised: they are written in full right after allocation.
using Keys = std::unique_ptr<uint64_t[]>;

void sortByCode(Keys &keys, std::size_t n) {
    constexpr int kDigitBits = 10;
    constexpr std::size_t kBuckets = std::size_t(1) << kDigitBits;
    Keys other(new uint64_t[n]);
    std::vector<uint32_t> start(kBuckets);
    for (int shift = 32; shift < 32 + 3 * kBitsPerAxis; shift += kDigitBits) {
        std::fill(start.begin(), start.end(), 0u);
        for (std::size_t i = 0; i < n; ++i) ++start[(keys[i] >> shift) & (kBuckets - 1)];
        uint32_t sum = 0;
        for (uint32_t &s : start) sum += std::exchange(s, sum);
        for (std::size_t i = 0; i < n; ++i) other[start[(keys[i] >> shift) & (kBuckets - 1)]++] = keys[i];
        keys.swap(other);
    }
}

class MortonBuilder {
public:
    MortonBuilder(const uint64_t *keys, const BuildPrim *boxes, BvhNode *slots, int maxLeaf,
                  bool parallel)
        : m_keys(keys), m_boxes(boxes), m_slots(slots), m_maxLeaf(uint32_t(maxLeaf)), m_parallel(parallel) {}

    /// What a subtree holds besides its nodes: counted on the way back up, not in shared
    /// counters that two threads would pass one cache line back and forth for.
    struct Subtree {
        std::size_t leaves = 0;
        int depth = 0; ///< of its deepest node, counted from the root
    };

    /// Builds the subtree of sorted keys [begin, end) into `slot`, bounds and layer mask included.
    Subtree build(uint32_t slot, uint32_t begin, uint32_t end, int depth) {
        BvhNode &node = m_slots[slot];
        const uint32_t n = end - begin;
        if (n <= m_maxLeaf) {
            makeLeaf(node, begin, n);
            return {1, depth};
        }
        // A range that two leaves can hold is halved: split by its codes it would often leave a
        // leaf of one and another of several, more leaves (blocks) for the same primitives.
        const uint32_t mid = n <= 2 * m_maxLeaf ? begin + n / 2 : splitOf(begin, end);
        const uint32_t base = m_nextSlot.fetch_add(2, std::memory_order_relaxed);
        Subtree left, right;
        if (m_parallel && n >= kMinParallelPrims)
            tbb::parallel_invoke([&] { left = build(base, begin, mid, depth + 1); },
                                 [&] { right = build(base + 1, mid, end, depth + 1); });
        else {
            left = build(base, begin, mid, depth + 1);
            right = build(base + 1, mid, end, depth + 1);
        }
        const BvhNode &a = m_slots[base], &b = m_slots[base + 1];
        for (int k = 0; k < 3; ++k) {
            node.bounds[k] = std::min(a.bounds[k], b.bounds[k]);
            node.bounds[k + 3] = std::max(a.bounds[k + 3], b.bounds[k + 3]);
        }
        node.layerMask = a.layerMask | b.layerMask;
        node.index = base;
        return {left.leaves + right.leaves, std::max(left.depth, right.depth)};
    }

    uint32_t slotsUsed() const { return m_nextSlot.load(); }

private:
    uint32_t codeAt(uint32_t i) const { return uint32_t(m_keys[i] >> 32); }

    /// The first index of the upper half: where the highest bit that differs between the range's
    /// first and last codes turns from 0 to 1 (the codes are sorted, so it turns once); the
    /// median when every code is the same.
    uint32_t splitOf(uint32_t begin, uint32_t end) const {
        const uint32_t first = codeAt(begin), last = codeAt(end - 1);
        if (first == last) return begin + (end - begin) / 2;
        const uint32_t bit = uint32_t(1) << (31 - std::countl_zero(first ^ last));
        uint32_t lo = begin + 1, hi = end - 1; // the answer lies in (begin, end − 1]
        while (lo < hi) {
            const uint32_t m = lo + (hi - lo) / 2;
            if (codeAt(m) & bit) hi = m;
            else lo = m + 1;
        }
        return lo;
    }

    void makeLeaf(BvhNode &node, uint32_t begin, uint32_t n) {
        Box4 box;
        uint32_t mask = 0;
        for (uint32_t i = begin; i < begin + n; ++i) {
            const BuildPrim &p = m_boxes[i];
            const PrimLanes lanes(p);
            box.grow(lanes.lo, lanes.hi);
            mask |= p.layerBit;
        }
        const glm::vec3 lo = box.min(), hi = box.max();
        node.bounds[0] = lo.x, node.bounds[1] = lo.y, node.bounds[2] = lo.z;
        node.bounds[3] = hi.x, node.bounds[4] = hi.y, node.bounds[5] = hi.z;
        node.layerMask = mask;
        node.index = (n << BvhNode::kCountShift) | begin;
    }

    const uint64_t *m_keys;
    const BuildPrim *m_boxes;
    BvhNode *m_slots;
    uint32_t m_maxLeaf;
    bool m_parallel;
    std::atomic<uint32_t> m_nextSlot{1}; ///< slot 0 is the root
};

} // namespace

Bvh buildMortonBvh(BvhBuildInput input) {
    Bvh bvh;
    const std::size_t n = input.prims.size();
    if (n == 0) return bvh;
    const BuildPrims boxes = makeBuildPrims(input.prims, input.threads, input.pages);
    // The centroids' grid, with the binning's guard against extents that overflow or vanish
    // (such an axis contributes no bits: its primitives are told apart by the other axes).
    const glm::vec3 clo = boxes.bounds.cbox.min(), chi = boxes.bounds.cbox.max();
    glm::vec3 scale(0.f);
    constexpr float kCells = float(1 << kBitsPerAxis);
    for (int axis = 0; axis < 3; ++axis) {
        const float extent = chi[axis] - clo[axis];
        const float s = extent > 0.f ? kCells * (1.f - 1.f / 4096.f) / extent : 0.f;
        scale[axis] = std::isfinite(s) ? s : 0.f;
    }
    Keys keys(new uint64_t[n]);
    mvcl::parallelForChunks(n, input.threads, 16384, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const PrimLanes p(boxes.prims[i]);
            uint32_t code = 0;
            for (int axis = 0; axis < 3; ++axis) {
                const float cell = (p.centroid(axis) - clo[axis]) * scale[axis];
                // NaN (∞·0 on an overflowing axis) and rounding past either end land in a grid cell.
                const uint32_t q = cell >= 1.f ? std::min(uint32_t(cell), uint32_t(kCells) - 1) : 0u;
                code |= spreadBits(q) << (2 - axis);
            }
            keys[i] = uint64_t(code) << 32 | uint32_t(i);
        }
    });
    sortByCode(keys, n);
    // The boxes in the sorted order, gathered once by independent loads (in the tree's leaves,
    // each would be a cache miss on the recursion's path).
    const std::unique_ptr<BuildPrim[], AlignedFree> sorted(static_cast<BuildPrim *>(allocateAligned(n * sizeof(BuildPrim), input.pages)));
    mvcl::parallelForChunks(n, input.threads, 16384, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) sorted[i] = boxes.prims[uint32_t(keys[i])];
    });

    const int maxLeaf = std::min(std::clamp(input.maxLeafSize, 1, int(BvhNode::kMaxLeafCount)), int(kBlockSize));
    bvh.nodes.reset(static_cast<BvhNode *>(allocateAligned(2 * n * sizeof(BvhNode), input.pages)));
    bvh.pages = input.pages;
    const auto build = [&](bool parallel) {
        MortonBuilder builder(keys.get(), sorted.get(), bvh.nodes.get(), maxLeaf, parallel);
        const MortonBuilder::Subtree tree = builder.build(0, 0, uint32_t(n), 0);
        bvh.nodeCount = builder.slotsUsed();
        bvh.leafCount = tree.leaves;
        bvh.maxDepth = tree.depth;
    };
    if (input.threads > 1) workerArena(input.threads).execute([&] { build(true); });
    else build(false);

    bvh.order.resize(n);
    for (std::size_t i = 0; i < n; ++i) bvh.order[i] = uint32_t(keys[i]);
    bvh.prims = std::move(input.prims);
    return bvh;
}

} // namespace mvcl::detail
