// Collapse of the binary SAH tree into the 8-wide traversal tree, in parallel: the top wide
// levels are collapsed serially, every subtree below them is a task. A first parallel pass
// counts each task's wide nodes and leaf blocks, a prefix sum places the tasks, and a second
// parallel pass writes them. The layout depends only on the tree (top nodes first, then the
// tasks in depth-first order, each task's output contiguous and depth-first), never on the
// thread count.

#include "WideBvh.h"

#include <mvcl/core/WorkerPool.h>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <new>

namespace mvcl::detail {

namespace {

/// Wide levels collapsed serially; up to 8^kTopLevels tasks, enough to balance any few threads.
constexpr int kTopLevels = 2;

float area(const BvhNode &n) {
    const float dx = n.bounds[3] - n.bounds[0];
    const float dy = n.bounds[4] - n.bounds[1];
    const float dz = n.bounds[5] - n.bounds[2];
    return dx * dy + dy * dz + dz * dx;
}

template <class T>
std::unique_ptr<T[], AlignedFree> allocateArray(std::size_t count, Pages pages) {
    return std::unique_ptr<T[], AlignedFree>(
        static_cast<T *>(allocateAligned(std::max<std::size_t>(1, count) * sizeof(T), pages)));
}

uint32_t blocksOfLeaf(const BvhNode &leaf) { return (leaf.count() + 3) / 4; }

/// The binary nodes that become the children of the wide node for interior node `n2`: its
/// children, then repeatedly the interior one with the largest surface area is replaced by its
/// own two children. Returns how many (2..kWidth).
int selectKids(const BvhNode *nodes, uint32_t n2, uint32_t kids[kWidth]) {
    kids[0] = nodes[n2].offset();
    kids[1] = nodes[n2].offset() + 1;
    int count = 2;
    while (count < kWidth) {
        int best = -1;
        float bestArea = -1.f;
        for (int i = 0; i < count; ++i) {
            const BvhNode &k = nodes[kids[i]];
            if (!k.isLeaf() && area(k) > bestArea) bestArea = area(k), best = i;
        }
        if (best < 0) break;
        const uint32_t first = nodes[kids[best]].offset();
        kids[best] = first;
        kids[count++] = first + 1;
    }
    return count;
}

/// A subtree below the serial top: binary node `node` (leaf or interior) whose reference goes
/// into lane `lane` of wide node `parent` (or becomes the root when parent is ~0).
struct Task {
    uint32_t node;
    uint32_t parent;
    int lane;
    uint32_t nodeCount = 0; ///< wide nodes of the subtree
    uint32_t blockCount = 0;
    uint32_t nodeBase = 0;
    uint32_t blockBase = 0;
};

class Collapser {
public:
    Collapser(const Bvh &bvh, WideBvh &out, uint32_t nodeBase, uint32_t blockBase)
        : m_nodes(bvh.nodes.get()), m_prims(bvh.prims), m_order(bvh.order), m_out(out),
          m_nextNode(nodeBase), m_nextBlock(blockBase) {}

    /// The child reference of binary node `n2` (a leaf, or the wide subtree collapsed from it).
    uint32_t reference(uint32_t n2) {
        const BvhNode &k = m_nodes[n2];
        return k.isLeaf() ? packLeaf(k) : collapse(n2);
    }

    /// Builds the wide node for binary interior node `n2` and, below `levels` more wide levels,
    /// its subtrees (levels < 0: all of them); children left out are recorded in `tasks`.
    uint32_t collapse(uint32_t n2, int levels = -1, std::vector<Task> *tasks = nullptr) {
        uint32_t kids[kWidth];
        const int count = selectKids(m_nodes, n2, kids);
        const uint32_t index = m_nextNode++;
        WideNode &node = m_out.nodes[index];
        for (int lane = 0; lane < kWidth; ++lane) {
            if (lane >= count) {
                for (int a = 0; a < 3; ++a) {
                    node.bounds[a][lane] = std::numeric_limits<float>::infinity();
                    node.bounds[a + 3][lane] = -std::numeric_limits<float>::infinity();
                }
                node.child[lane] = 0;
                node.layerMask[lane] = 0;
                continue;
            }
            const BvhNode &k = m_nodes[kids[lane]];
            for (int a = 0; a < 6; ++a) node.bounds[a][lane] = k.bounds[a];
            node.layerMask[lane] = k.layerMask;
            if (levels == 0 || (levels > 0 && k.isLeaf())) {
                tasks->push_back(Task{kids[lane], index, lane});
                node.child[lane] = 0; // patched once the task is written
            } else {
                // Written through the index: recursion does not move the node array.
                node.child[lane] = k.isLeaf() ? packLeaf(k) : collapse(kids[lane], levels - 1, tasks);
            }
        }
        return index;
    }

    /// Copies a binary leaf's primitives into consecutive blocks; returns the leaf reference.
    uint32_t packLeaf(const BvhNode &leaf) {
        const uint32_t first = m_nextBlock;
        const uint32_t count = leaf.count();
        const uint32_t blocks = blocksOfLeaf(leaf);
        bool hasSpheres = false;
        for (uint32_t b = 0; b < blocks; ++b) {
            PrimBlock &block = m_out.blocks[first + b];
            for (int lane = 0; lane < 4; ++lane) {
                const uint32_t i = 4 * b + uint32_t(lane);
                PrimInfo &info = m_out.info[4 * std::size_t(first + b) + lane];
                if (i >= count) {
                    for (int k = 0; k < 3; ++k) block.setVertex(lane, k, glm::vec3(0.f));
                    block.triangleLayerBit[lane] = 0;
                    info = PrimInfo{0, 0, uint8_t(PrimKind::Empty), 0, 0};
                    continue;
                }
                const PrimRecord &p = m_prims[m_order[leaf.offset() + i]];
                block.setVertex(lane, 0, p.p0);
                block.setVertex(lane, 1, p.p1);
                block.setVertex(lane, 2, p.p2);
                const bool sphere = p.kind == uint8_t(PrimKind::Sphere);
                hasSpheres |= sphere;
                block.triangleLayerBit[lane] = sphere ? 0u : 1u << p.layer;
                info = PrimInfo{p.geometry, p.primitive, p.kind, p.layer, 0};
            }
        }
        m_nextBlock += blocks;
        return WideLeaf::encode(first, blocks, hasSpheres);
    }

    uint32_t nextNode() const { return m_nextNode; }
    uint32_t nextBlock() const { return m_nextBlock; }

private:
    const BvhNode *m_nodes;
    const PrimArray &m_prims;
    const std::vector<uint32_t> &m_order;
    WideBvh &m_out;
    uint32_t m_nextNode;
    uint32_t m_nextBlock;
};

/// Wide nodes and leaf blocks of the subtree of binary node `n2`, as collapse() will emit them.
void countSubtree(const BvhNode *nodes, uint32_t n2, uint32_t &wideNodes, uint32_t &blocks) {
    const BvhNode &n = nodes[n2];
    if (n.isLeaf()) {
        blocks += blocksOfLeaf(n);
        return;
    }
    ++wideNodes;
    uint32_t kids[kWidth];
    const int count = selectKids(nodes, n2, kids);
    for (int i = 0; i < count; ++i) countSubtree(nodes, kids[i], wideNodes, blocks);
}

} // namespace

WideBvh collapseToWide(const Bvh &bvh, int threads) {
    WideBvh out;
    if (bvh.nodeCount == 0) return out;
    const BvhNode &root = bvh.nodes[0];
    for (int a = 0; a < 6; ++a) out.rootBounds[a] = root.bounds[a];
    out.rootMask = root.layerMask;
    // Upper bound for the top: a wide node replaces at least one binary interior node (there
    // are leafCount − 1 of those).
    out.nodes = allocateArray<WideNode>(bvh.leafCount, bvh.pages);

    std::vector<Task> tasks;
    uint32_t topNodes = 0;
    {
        Collapser top(bvh, out, 0, 0);
        if (root.isLeaf()) tasks.push_back(Task{0, ~0u, 0});
        else out.root = top.collapse(0, kTopLevels - 1, &tasks);
        topNodes = top.nextNode();
    }
    mvcl::parallelFor(tasks.size(), threads, [&](std::size_t i) {
        countSubtree(bvh.nodes.get(), tasks[i].node, tasks[i].nodeCount, tasks[i].blockCount);
    });
    uint32_t nodeCount = topNodes, blockCount = 0;
    for (Task &t : tasks) {
        t.nodeBase = nodeCount;
        t.blockBase = blockCount;
        nodeCount += t.nodeCount;
        blockCount += t.blockCount;
    }
    out.nodeCount = nodeCount;
    out.blockCount = blockCount;
    out.blocks = allocateArray<PrimBlock>(blockCount, bvh.pages);
    // Not value-initialised: the tasks below write every lane, each on its own thread.
    out.info = allocateArray<PrimInfo>(4 * std::size_t(blockCount), bvh.pages);
    mvcl::parallelFor(tasks.size(), threads, [&](std::size_t i) {
        const Task &t = tasks[i];
        Collapser c(bvh, out, t.nodeBase, t.blockBase);
        const uint32_t ref = c.reference(t.node);
        if (t.parent == ~0u) out.root = ref;
        else out.nodes[t.parent].child[t.lane] = ref;
    });
    return out;
}

} // namespace mvcl::detail
