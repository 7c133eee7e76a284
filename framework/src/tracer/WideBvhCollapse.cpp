// Collapse of the binary SAH tree into the 8-wide traversal tree, in parallel: the top wide
// levels are collapsed serially, every subtree below them is a task. A first parallel pass
// counts each task's wide nodes and leaf blocks, a prefix sum places the tasks, and a second
// parallel pass writes them. The layout depends only on the tree (top nodes first, then the
// tasks in depth-first order, each task's output contiguous and depth-first), never on the
// thread count.

#include "WideBvh.h"

#include <mvcl/core/WorkerPool.h>

#include <algorithm>
#include <cmath>
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
std::unique_ptr<T[], AlignedFree> allocateArray(std::size_t count) {
    return std::unique_ptr<T[], AlignedFree>(
        static_cast<T *>(allocateAligned(std::max<std::size_t>(1, count) * sizeof(T))));
}

/// The grid of one axis of a quantised node (WideNode): exponent field and origin bias.
struct AxisGrid {
    uint8_t exponent = 1;
    float bias = std::numeric_limits<float>::quiet_NaN(); ///< NaN: no grid fits, axis untested
};

/// The finest grid step s = 2^e whose 256 points k·s … (k + 255)·s, k = floor(lo / s), reach
/// hi and are all floats, with 2^23·s and the bias (k − 2^23)·s floats too (the conditions of
/// WideNode's exact dequantisation). Done in double, where every value here is exact (floats
/// scaled by powers of two, integers below 2^25). No grid for extents beyond ~2^112 or
/// non-finite bounds: the axis is then left untested (NaN bias).
AxisGrid axisGrid(float lo, float hi) {
    AxisGrid g;
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo <= hi)) return g;
    // Start at the step the extent needs, or the one the magnitude needs (|k| < 2^23), the
    // larger; a step or two more at most when rounding pushes hi past the last point.
    const double extent = double(hi) - double(lo);
    const double magnitude = std::max(std::fabs(double(lo)), std::fabs(double(hi)));
    int e = -149;
    if (extent > 0.0) e = std::max(e, std::ilogb(extent / 255.0));
    if (magnitude > 0.0) e = std::max(e, std::ilogb(magnitude) - 23);
    for (; e <= 104; ++e) {
        const double step = std::ldexp(1.0, e);
        const double k = std::floor(double(lo) / step);
        if (k <= -8388608.0 || k + 255.0 > 16777216.0) continue; // (k − 2^23) and (k + q) fit 24 bits
        if (std::ceil(double(hi) / step) - k > 255.0) continue;
        g.exponent = uint8_t(e + 150);
        g.bias = float((k - 8388608.0) * step);
        // The float dequantisation itself must reach hi (it is exact, so this only restates the
        // double arithmetic above; kept as the guarantee the traversal relies on).
        if (WideNode::dequantize(255, g.exponent, g.bias) >= hi && WideNode::dequantize(0, g.exponent, g.bias) <= lo)
            return g;
    }
    return AxisGrid{};
}

/// The largest grid value whose dequantised bound is ≤ v (lower bounds round down).
uint8_t quantizeDown(float v, const AxisGrid &g) {
    if (std::isnan(g.bias)) return 0;
    int q = int(std::clamp(std::floor((double(v) - double(WideNode::dequantize(0, g.exponent, g.bias))) /
                                      std::ldexp(1.0, int(g.exponent) - 150)),
                           0.0, 255.0));
    while (q > 0 && WideNode::dequantize(uint8_t(q), g.exponent, g.bias) > v) --q;
    while (q < 255 && WideNode::dequantize(uint8_t(q + 1), g.exponent, g.bias) <= v) ++q;
    return uint8_t(q);
}

/// The smallest grid value whose dequantised bound is ≥ v (upper bounds round up).
uint8_t quantizeUp(float v, const AxisGrid &g) {
    if (std::isnan(g.bias)) return 255;
    int q = int(std::clamp(std::ceil((double(v) - double(WideNode::dequantize(0, g.exponent, g.bias))) /
                                     std::ldexp(1.0, int(g.exponent) - 150)),
                           0.0, 255.0));
    while (q < 255 && WideNode::dequantize(uint8_t(q), g.exponent, g.bias) < v) ++q;
    while (q > 0 && WideNode::dequantize(uint8_t(q - 1), g.exponent, g.bias) >= v) --q;
    return uint8_t(q);
}

/// Fills the grid and the quantised boxes of `node` from the exact child boxes of its first
/// `count` lanes; the other lanes get the empty box (lower 255 > upper 0).
void quantizeNode(WideNode &node, const BvhNode *const kids[kWidth], int count) {
    node.pad = 0;
    for (int a = 0; a < 3; ++a) {
        float lo = std::numeric_limits<float>::infinity(), hi = -lo;
        for (int lane = 0; lane < count; ++lane) {
            lo = std::min(lo, kids[lane]->bounds[a]);
            hi = std::max(hi, kids[lane]->bounds[a + 3]);
        }
        const AxisGrid g = axisGrid(lo, hi);
        node.stepExponent[a] = g.exponent;
        node.originBias[a] = g.bias;
        for (int lane = 0; lane < kWidth; ++lane) {
            if (lane >= count) {
                node.q[a][lane] = 255;
                node.q[a + 3][lane] = 0;
                continue;
            }
            node.q[a][lane] = quantizeDown(kids[lane]->bounds[a], g);
            node.q[a + 3][lane] = quantizeUp(kids[lane]->bounds[a + 3], g);
        }
    }
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
        const BvhNode *kidNodes[kWidth];
        for (int lane = 0; lane < count; ++lane) kidNodes[lane] = &m_nodes[kids[lane]];
        quantizeNode(node, kidNodes, count);
        for (int lane = 0; lane < kWidth; ++lane) {
            if (lane >= count) {
                node.child[lane] = 0;
                node.layerMask[lane] = 0;
                continue;
            }
            const BvhNode &k = m_nodes[kids[lane]];
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
    out.nodes = allocateArray<WideNode>(bvh.leafCount);

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
    out.blocks = allocateArray<PrimBlock>(blockCount);
    // Not value-initialised: the tasks below write every lane, each on its own thread.
    out.info = allocateArray<PrimInfo>(4 * std::size_t(blockCount));
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
