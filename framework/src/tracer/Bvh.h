#pragma once
// Private: the flattened BVH the tracer traverses, and the primitive records in leaf order.

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <vector>

namespace mvcl::detail {

/// 32 bytes. A node of the binary build tree (traversal walks the 8-wide WideNode collapsed
/// from it).
struct alignas(32) BvhNode {
    float bounds[6];    ///< min x, y, z, max x, y, z
    uint32_t index;     ///< bits 31..28: leaf primitive count (0 = interior); bits 27..0: first
                        ///< child (interior) or first primitive record (leaf)
    uint32_t layerMask; ///< union of the layer bits of every primitive below

    static constexpr uint32_t kCountShift = 28;
    static constexpr uint32_t kOffsetMask = (1u << kCountShift) - 1u;
    static constexpr uint32_t kMaxLeafCount = 15;

    uint32_t count() const { return index >> kCountShift; }
    uint32_t offset() const { return index & kOffsetMask; }
    bool isLeaf() const { return count() != 0; }
};
static_assert(sizeof(BvhNode) == 32);

/// Empty marks an unused lane of a PrimBlock.
enum class PrimKind : uint8_t { Triangle = 0, Sphere = 1, Empty = 2 };

/// 48 bytes, in leaf order: what a leaf needs to intersect without touching the Scene.
struct PrimRecord {
    glm::vec3 p0; ///< triangle vertex 0, or sphere centre
    glm::vec3 p1; ///< triangle vertex 1, or (radius, 0, 0)
    glm::vec3 p2; ///< triangle vertex 2
    uint32_t geometry;
    uint32_t primitive;
    uint8_t kind; ///< PrimKind
    uint8_t layer;
    uint16_t pad;
};
static_assert(sizeof(PrimRecord) == 48);

static_assert(std::is_trivially_default_constructible_v<PrimRecord>);

struct AlignedFree {
    void operator()(void *p) const;
};

/// Which pages large arrays take. Huge pages make a build that reuses warm memory and the
/// queries faster (fewer TLB misses), but a process's first touch of fresh huge pages can cost
/// more than it saves: in the viewer, opening a 1.18M-triangle model, the quick build took twice
/// its CPU time on them, most of it the kernel zeroing 2 MiB pages. The quick build, whose
/// point is latency, takes small pages.
enum class Pages { HugeWhenLarge, Small };

/// 64-byte aligned memory for node and leaf arrays (a node never straddles more cache lines
/// than it must), released with AlignedFree. Not initialised. With Pages::HugeWhenLarge, arrays
/// of 1 MiB or more go on transparent huge pages when the system allows it, like a render
/// session's large buffers (allocateLargeBuffer, src/core/HugePageAllocator_p.h).
void *allocateAligned(std::size_t bytes, Pages pages = Pages::HugeWhenLarge);

/// The build input records. Not a std::vector: they are written by parallel chunks right after
/// allocation, and value-initialising hundreds of thousands first would be a serial pass.
struct PrimArray {
    std::unique_ptr<PrimRecord[], AlignedFree> data;
    std::size_t count = 0;

    void allocate(std::size_t n, Pages pages) {
        data.reset(static_cast<PrimRecord *>(allocateAligned(n * sizeof(PrimRecord), pages)));
        count = n;
    }
    std::size_t size() const { return count; }
    PrimRecord &operator[](std::size_t i) { return data[i]; }
    const PrimRecord &operator[](std::size_t i) const { return data[i]; }
};

/// The binary SAH tree. Node 0 is the root; the children of an interior node are the adjacent
/// pair (offset, offset + 1). Pairs are allocated as tasks reach them, so slot positions (unlike
/// the tree itself) may differ between builds with different thread counts; the wide collapse
/// walks the tree depth first and lays out its output independently of them.
struct Bvh {
    std::unique_ptr<BvhNode[], AlignedFree> nodes;
    std::size_t nodeCount = 0; ///< slots in use (all of [0, nodeCount) are valid nodes)
    std::size_t leafCount = 0;
    int maxDepth = 0;
    PrimArray prims;             ///< the build input, in input order
    std::vector<uint32_t> order;   ///< leaf order: a leaf's primitives are prims[order[offset + i]]
    Pages pages = Pages::HugeWhenLarge; ///< the build's, for the arrays made from the tree too
};

struct BvhBuildInput {
    PrimArray prims; ///< any order; only valid (finite, non-degenerate) ones
    int maxLeafSize = 4;
    int threads = 1;
    Pages pages = Pages::HugeWhenLarge; ///< of the build's arrays and the output's
};

/// Binned SAH build with leaf costs counted in blocks of four primitives (what the 4-wide
/// triangle kernel tests at once), multithreaded over subtrees (tasks on the worker pool).
/// Deterministic: the tree does not depend on the thread count.
Bvh buildBvh(BvhBuildInput input);

/// The quick build (MortonBvhBuilder.cpp): primitives sorted along a Morton curve and split where
/// their codes' highest differing bit changes. Several times faster to build than buildBvh, slower
/// to trace; deterministic in the same way. The same output, so the same collapse.
Bvh buildMortonBvh(BvhBuildInput input);

} // namespace mvcl::detail
