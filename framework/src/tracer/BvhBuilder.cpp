// Binned SAH BVH build (Wald 2007 style binning, up to 32 bins, all three axes in one pass),
// parallel over subtrees: every node of at least kMinParallelPrims pushes one child as a task of
// the framework's worker pool (a tbb::task_group in its arena), at any depth, so no large subtree
// is left to one thread at the end. Each node receives its bounds and centroid bounds from its
// parent (the partition pass computes them for both children), so a node reads its primitives
// twice: once to bin, once to partition. The tree depends only on the input, never on the
// thread count; only the slots of child pairs (taken from an atomic counter) do, and the wide
// collapse lays out its output independently of them. The binning (with the SAH sweep) and the
// partition run with AVX2 when the CPU has it (BvhBuildAvx2.cpp, through KernelTables.h), and
// build the same tree as the SSE2 code here.

#include "Bvh.h"
#include "BvhBuild.h"
#include "KernelTables.h"
#include "core/HugePageAllocator_p.h"
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

namespace mvcl::detail {

void AlignedFree::operator()(void *p) const { std::free(p); }

void *allocateAligned(std::size_t bytes, Pages pages) {
    if (pages == Pages::HugeWhenLarge) return allocateLargeBuffer(bytes);
    void *p = std::aligned_alloc(64, std::max<std::size_t>(64, (bytes + 63) / 64 * 64));
    if (!p) throw std::bad_alloc();
    return p;
}

namespace {
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
/// SAH cost of a sphere in a leaf, beyond its lane of a block (see build()).
constexpr double kSphereCost = 1.0;

uint32_t blocksOf(uint32_t count) { return (count + kBlockSize - 1) / kBlockSize; }

double halfArea(const glm::vec3 &lo, const glm::vec3 &hi) {
    const double dx = double(hi.x) - double(lo.x);
    const double dy = double(hi.y) - double(lo.y);
    const double dz = double(hi.z) - double(lo.z);
    return dx * dy + dy * dz + dz * dx;
}

RangeBounds boundsOf(const BuildPrim *prims, uint32_t begin, uint32_t end) {
    RangeBounds r;
    for (uint32_t i = begin; i < end; ++i) r.grow(PrimLanes(prims[i]));
    return r;
}

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

/// Subtree builds are pushed as tasks whenever a node is large enough, at any depth, and idle
/// threads take them: with a fixed spawn depth a single large subtree below it kept one core busy
/// while the other waited at the end of the build. Tasks never wait for one another (results
/// that need both children are fixed up by finishLayerMasks() after the group is done), so there
/// are no joins inside the tree.
class Builder {
public:
    /// tasks: where subtrees are pushed (null: build everything on the calling thread). All
    /// calls then run inside the worker arena the group's tasks are spawned in.
    /// records: the primitives the BuildPrims' ids index (their kinds price the leaves).
    Builder(BuildPrim *prims, const PrimArray &records, BvhNode *slots, int maxLeaf, tbb::task_group *tasks)
        : m_prims(prims), m_records(records), m_slots(slots), m_maxLeaf(maxLeaf), m_tasks(tasks) {}

    /// Builds the subtree of [begin, end) into `slot`; `bounds` are that range's bounds.
    void build(uint32_t slot, uint32_t begin, uint32_t end, int depth, const RangeBounds &bounds) {
        const glm::vec3 lo = bounds.box.min(), hi = bounds.box.max();
        const glm::vec3 clo = bounds.cbox.min(), chi = bounds.cbox.max();
        BvhNode &node = m_slots[slot];
        node.bounds[0] = lo.x, node.bounds[1] = lo.y, node.bounds[2] = lo.z;
        node.bounds[3] = hi.x, node.bounds[4] = hi.y, node.bounds[5] = hi.z;
        noteDepth(depth);

        const uint32_t n = end - begin;
        // A leaf costs its blocks, and each sphere as much again as a block: the 4-wide triangle
        // test takes a block at once, but a sphere's roots are a chain of divisions and a square
        // root in double. Priced as one lane, cube-in-cube's two spheres shared a leaf with two
        // triangles, its box spanning both spheres: nine leaf visits in ten went there and paid
        // both spheres (docs/benchmarks.md).
        const double leafCost = n <= uint32_t(m_maxLeaf)
                                    ? double(blocksOf(n)) + kSphereCost * double(spheresIn(begin, end))
                                    : std::numeric_limits<double>::infinity();
        // A split costs the traversal step plus at least one block per side, more than the
        // single block of a leaf of up to four triangles: such a node is a leaf whatever
        // findSplit finds.
        if (n <= std::min<uint32_t>(uint32_t(m_maxLeaf), kBlockSize) && leafCost <= 1.0)
            return makeLeaf(node, begin, n);

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
        if (n <= uint32_t(m_maxLeaf) && leafCost <= splitCost) return makeLeaf(node, begin, n);

        uint32_t mid;
        RangeBounds left, right;
        if (bestAxis >= 0) {
            if (m_fast) mid = m_fast->partition(binner, bestAxis, bestSplit, m_prims, begin, end, left, right);
            else mid = partition(binner, bestAxis, bestSplit, begin, end, left, right);
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
        if (m_fast) return findSplitFast(binner, begin, end, halves, bestAxis, bestSplit, bestCost);
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

    /// findSplit with m_fast's binning and sweep, the halves binned as two tasks as above.
    void findSplitFast(const Binner &binner, uint32_t begin, uint32_t end, bool halves, int &bestAxis,
                       int &bestSplit, double &bestCost) const {
        if (!halves) return m_fast->findSplit(binner, m_prims, begin, end, bestAxis, bestSplit, bestCost);
        BinStorage all, upper; // made by m_fast->bin()
        const uint32_t mid = begin + (end - begin) / 2;
        tbb::this_task_arena::isolate([&] {
            tbb::parallel_invoke([&] { m_fast->bin(binner, m_prims, begin, mid, all); },
                                 [&] { m_fast->bin(binner, m_prims, mid, end, upper); });
        });
        m_fast->merge(all, upper, binner.nBins);
        m_fast->sweep(binner, all, bestAxis, bestSplit, bestCost);
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

    /// Spheres among the primitives [begin, end) (only asked for ranges that may be leaves).
    uint32_t spheresIn(uint32_t begin, uint32_t end) const {
        uint32_t spheres = 0;
        for (uint32_t i = begin; i < end; ++i) spheres += m_records[m_prims[i].id].kind == uint8_t(PrimKind::Sphere);
        return spheres;
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
    const PrimArray &m_records;
    BvhNode *m_slots;
    int m_maxLeaf;
    tbb::task_group *m_tasks;
    /// The AVX2 binning and partition when the CPU has AVX2 (BvhBuildAvx2.cpp), else null: the
    /// SSE2 ones above. Chosen once per build.
    const BuildKernels *m_fast = buildKernels();
    std::mutex m_spawnedMutex;
    std::vector<std::pair<int, uint32_t>> m_spawned; ///< (depth, slot) of nodes that spawned
    std::atomic<uint32_t> m_nextSlot{1}; ///< slot 0 is the root
    std::atomic<int> m_maxDepth{0};
    std::atomic<std::size_t> m_leafCount{0};
};

std::unique_ptr<BvhNode[], AlignedFree> allocateNodes(std::size_t count, Pages pages) {
    return std::unique_ptr<BvhNode[], AlignedFree>(
        static_cast<BvhNode *>(allocateAligned(count * sizeof(BvhNode), pages)));
}

} // namespace

BuildPrims makeBuildPrims(const PrimArray &prims, int threads, Pages pages) {
    const std::size_t n = prims.size();
    if (n >= (std::size_t(1) << (BvhNode::kCountShift - 1)))
        throw Error("tracer", "too many primitives for the BVH (" + std::to_string(n) + ")");
    BuildPrims out;
    // Not value-initialised: the chunks below write every record.
    out.prims.reset(static_cast<BuildPrim *>(allocateAligned(std::max<std::size_t>(1, n) * sizeof(BuildPrim), pages)));
    // Boxes in parallel chunks; the bounds of all are merged from per-chunk bounds (min/max is
    // exact in any order).
    constexpr std::size_t kChunk = 16384;
    const std::size_t chunks = (n + kChunk - 1) / kChunk;
    std::vector<RangeBounds> chunkBounds(chunks);
    mvcl::parallelFor(chunks, threads, [&](std::size_t c) {
        const std::size_t end = std::min(n, (c + 1) * kChunk);
        RangeBounds bounds; // local: neighbouring chunks' bounds share cache lines
        for (std::size_t i = c * kChunk; i < end; ++i) {
            const PrimRecord &r = prims[i];
            BuildPrim &b = out.prims[i];
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
    for (const RangeBounds &cb : chunkBounds) {
        out.bounds.box.grow(cb.box);
        out.bounds.cbox.grow(cb.cbox);
    }
    return out;
}

Bvh buildBvh(BvhBuildInput input) {
    Bvh bvh;
    const std::size_t n = input.prims.size();
    if (n == 0) return bvh;
    const BuildPrims boxes = makeBuildPrims(input.prims, input.threads, input.pages);
    BuildPrim *const build = boxes.prims.get();
    const RangeBounds &rootBounds = boxes.bounds;

    const int maxLeaf = std::clamp(input.maxLeafSize, 1, int(BvhNode::kMaxLeafCount));
    // At most n leaves, so at most 2n − 1 nodes; pages past the ones used are never touched.
    bvh.nodes = allocateNodes(2 * n, input.pages);
    bvh.pages = input.pages;
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
            Builder builder(build, input.prims, bvh.nodes.get(), maxLeaf, &tasks);
            tasks.run_and_wait([&] { builder.build(0, 0, uint32_t(n), 0, rootBounds); });
            builder.finishLayerMasks();
            keepStats(builder);
        });
    } else {
        Builder builder(build, input.prims, bvh.nodes.get(), maxLeaf, nullptr);
        builder.build(0, 0, uint32_t(n), 0, rootBounds);
        keepStats(builder);
    }

    bvh.order.resize(n);
    for (std::size_t i = 0; i < n; ++i) bvh.order[i] = build[i].id;
    bvh.prims = std::move(input.prims);
    return bvh;
}

} // namespace mvcl::detail
