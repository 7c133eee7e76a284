#pragma once
// Private: the 8-wide BVH the tracer traverses, collapsed from the binary SAH tree. The eight
// child boxes of a node (SoA layout) are tested at once with AVX2, or as two halves with SSE
// (WideTraversal.inl); rays average only a few node visits, so fewer, wider nodes shorten the
// dependent chain of node loads that dominates traversal. Leaves point at PrimBlocks.

#include "Bvh.h"
#include "KernelIsa.h"
#include "PrimBlock.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace mvcl::detail {

/// Children per node.
inline constexpr int kWidth = 8;

/// Traversal stack entries. The binary build bounds the depth (SAH up to 64 levels, then
/// object-median splits of at most 28 more); a wide node pushes at most kWidth − 1 entries and
/// spans at least one binary level, so 7 · 92 < 660 cannot overflow.
inline constexpr int kStackSize = 660;

/// 256 bytes (four cache lines). Lane i describes child i; an empty lane has an empty box and a
/// zero layer mask so no query ever enters it. Float boxes on purpose: 8-bit quantised boxes
/// (128-byte nodes) were measured slower, their dequantisation sitting on the latency-bound
/// chain of node loads (docs/benchmarks.md, "Node layout and build").
struct alignas(64) WideNode {
    float bounds[6][kWidth];     ///< [min x, min y, min z, max x, max y, max z][lane]
    uint32_t child[kWidth];      ///< WideLeaf encoding when the top bits are non-zero, else the
                                 ///< index of a WideNode
    uint32_t layerMask[kWidth];  ///< union of the layer bits below each child
};
static_assert(sizeof(WideNode) == 256);

/// A child reference that is a leaf: bits 31..28 the number of PrimBlocks (1..4), bits 27..1
/// the first block, bit 0 set when a lane of the leaf is a sphere (the 4-wide triangle kernel
/// skips sphere lanes; only then does the leaf need the scalar sphere loop).
struct WideLeaf {
    static constexpr uint32_t kCountShift = 28;
    static constexpr uint32_t kMaxBlocks = 4; ///< BvhNode::kMaxLeafCount primitives at most

    static uint32_t encode(uint32_t firstBlock, uint32_t blockCount, bool hasSpheres) {
        return (blockCount << kCountShift) | (firstBlock << 1) | uint32_t(hasSpheres);
    }
    static MVCL_KERNEL_INLINE bool isLeaf(uint32_t ref) { return (ref >> kCountShift) != 0; }
    static MVCL_KERNEL_INLINE uint32_t blockCount(uint32_t ref) { return ref >> kCountShift; }
    static MVCL_KERNEL_INLINE uint32_t firstBlock(uint32_t ref) { return (ref & ((1u << kCountShift) - 1u)) >> 1; }
    static MVCL_KERNEL_INLINE bool hasSpheres(uint32_t ref) { return ref & 1u; }
};

struct WideBvh {
    std::unique_ptr<WideNode[], AlignedFree> nodes;
    std::size_t nodeCount = 0;
    uint32_t root = 0;     ///< child reference of the root (a leaf for tiny scenes)
    uint32_t rootMask = 0; ///< layer mask of everything
    float rootBounds[6] = {};
    std::unique_ptr<PrimBlock[], AlignedFree> blocks; ///< leaf primitives, in traversal-DFS order
    std::size_t blockCount = 0;
    std::unique_ptr<PrimInfo[], AlignedFree> info; ///< 4 per block (written by the collapse)
};

/// Collapses a binary BVH (root at node 0) into an 8-wide one, pulling up the grandchildren with
/// the largest surface area first, and packs the leaves' primitives into PrimBlocks.
WideBvh collapseToWide(const Bvh &bvh, int threads);

} // namespace mvcl::detail
