#pragma once
// Private: the 8-wide BVH the tracer traverses, collapsed from the binary SAH tree. The eight
// child boxes of a node (SoA layout) are tested at once with AVX2, or as two halves with SSE
// (WideTraversal.inl); rays average only a few node visits, so fewer, wider nodes shorten the
// dependent chain of node loads that dominates traversal. Quantised child boxes keep a node at
// two cache lines. Leaves point at PrimBlocks.

#include "Bvh.h"
#include "PrimBlock.h"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace mvcl::detail {

/// Children per node.
inline constexpr int kWidth = 8;

/// 128 bytes (two cache lines): the first holds what the slab test reads, the second the
/// child references and layer masks. Child boxes are quantised to 8 bits per bound on a per-node,
/// per-axis grid (Embree's compressed nodes use the same idea; this encoding is our own):
///
///     bound = float(bits (stepExponent[a] << 23) | q) + originBias[a]
///
/// The float with exponent field E = stepExponent[a] and mantissa q is 2^23·s + q·s for the grid
/// step s = 2^(E − 150), and originBias[a] = (k − 2^23)·s with the grid origin k·s; the collapse
/// picks s and k so that every (k + q)·s, q in [0, 255], is a float. So the addition is exact,
/// dequantisation is one integer OR and one float add (no multiply, so FMA contraction cannot
/// touch it: builds with -ffp-contract=fast dequantise to the same bits), and the collapse rounds
/// q outward against these exact values: every dequantised box contains the child's exact box.
/// The slab arithmetic is monotone in the bound, so a ray enters every box it entered with the
/// exact bounds (only more node visits, never other hits).
///
/// An axis whose range no grid covers (extents near the float range) has originBias NaN: its
/// slabs give NaN distances, which every node test ignores (treated as inside), so such a node's
/// children pass that axis. Lane i describes child i; an empty lane has q lower 255 > upper 0
/// and a zero layer mask so no query ever enters it.
struct alignas(64) WideNode {
    float originBias[3];       ///< (k − 2^23)·s per axis (NaN: the axis is not tested)
    uint8_t stepExponent[3];   ///< float exponent field of 2^23·s per axis (1..254)
    uint8_t pad;
    uint8_t q[6][kWidth];      ///< [min x, min y, min z, max x, max y, max z][lane]
    uint32_t child[kWidth];    ///< WideLeaf encoding when the top bits are non-zero, else the
                               ///< index of a WideNode
    uint32_t layerMask[kWidth];///< union of the layer bits below each child

    /// Bound `slab` (0..5, as q) of child `lane`, dequantised.
    float bound(int slab, int lane) const {
        const int axis = slab < 3 ? slab : slab - 3;
        return dequantize(q[slab][lane], stepExponent[axis], originBias[axis]);
    }
    /// The grid value q on an axis with exponent field `exponent` and bias `bias` (exact).
    static float dequantize(uint8_t value, uint8_t exponent, float bias) {
        return std::bit_cast<float>((uint32_t(exponent) << 23) | value) + bias;
    }
};
static_assert(sizeof(WideNode) == 128);
static_assert(offsetof(WideNode, q) + sizeof(WideNode::q) == 64, "the slab test reads one cache line");

/// A child reference that is a leaf: bits 31..28 the number of PrimBlocks (1..4), bits 27..1
/// the first block, bit 0 set when a lane of the leaf is a sphere (the 4-wide triangle kernel
/// skips sphere lanes; only then does the leaf need the scalar sphere loop).
struct WideLeaf {
    static constexpr uint32_t kCountShift = 28;
    static constexpr uint32_t kMaxBlocks = 4; ///< BvhNode::kMaxLeafCount primitives at most

    static uint32_t encode(uint32_t firstBlock, uint32_t blockCount, bool hasSpheres) {
        return (blockCount << kCountShift) | (firstBlock << 1) | uint32_t(hasSpheres);
    }
    static bool isLeaf(uint32_t ref) { return (ref >> kCountShift) != 0; }
    static uint32_t blockCount(uint32_t ref) { return ref >> kCountShift; }
    static uint32_t firstBlock(uint32_t ref) { return (ref & ((1u << kCountShift) - 1u)) >> 1; }
    static bool hasSpheres(uint32_t ref) { return ref & 1u; }
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
