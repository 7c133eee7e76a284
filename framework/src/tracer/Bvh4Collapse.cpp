#include "Bvh4.h"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <new>

namespace mvcl::detail {

namespace {

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

class Collapser {
public:
    Collapser(const Bvh &bvh, Bvh4 &out) : m_nodes(bvh.nodes.get()), m_prims(bvh.prims), m_order(bvh.order), m_out(out) {}

    /// Builds the 4-wide node for binary interior node `n2`; returns its index.
    uint32_t collapse(uint32_t n2) {
        uint32_t kids[4] = {m_nodes[n2].offset(), m_nodes[n2].offset() + 1, 0, 0};
        int count = 2;
        while (count < 4) {
            int best = -1;
            float bestArea = -1.f;
            for (int i = 0; i < count; ++i) {
                const BvhNode &k = m_nodes[kids[i]];
                if (!k.isLeaf() && area(k) > bestArea) bestArea = area(k), best = i;
            }
            if (best < 0) break;
            const uint32_t first = m_nodes[kids[best]].offset();
            kids[best] = first;
            kids[count++] = first + 1;
        }
        const uint32_t index = uint32_t(m_out.nodeCount++);
        Bvh4Node &node = m_out.nodes[index];
        for (int lane = 0; lane < 4; ++lane) {
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
            // Written through the index: recursion does not move the node array.
            node.child[lane] = k.isLeaf() ? packLeaf(k) : collapse(kids[lane]);
        }
        return index;
    }

    /// Copies a binary leaf's primitives into consecutive blocks; returns the leaf reference.
    uint32_t packLeaf(const BvhNode &leaf) {
        const uint32_t first = uint32_t(m_out.blockCount);
        const uint32_t count = leaf.count();
        const uint32_t blocks = (count + 3) / 4;
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
        m_out.blockCount += blocks;
        return Bvh4Leaf::encode(first, blocks, hasSpheres);
    }

private:
    const BvhNode *m_nodes;
    const std::vector<PrimRecord> &m_prims;
    const std::vector<uint32_t> &m_order;
    Bvh4 &m_out;
};

} // namespace

Bvh4 collapseToBvh4(const Bvh &bvh) {
    Bvh4 out;
    if (bvh.nodeCount == 0) return out;
    const BvhNode &root = bvh.nodes[0];
    for (int a = 0; a < 6; ++a) out.rootBounds[a] = root.bounds[a];
    out.rootMask = root.layerMask;
    // Upper bounds: a 4-wide node replaces at least one binary interior node (there are
    // leafCount − 1 of those); a leaf of c primitives takes ⌈c/4⌉ ≤ 1 + c/4 blocks.
    out.nodes = allocateArray<Bvh4Node>(bvh.leafCount);
    const std::size_t maxBlocks = bvh.leafCount + bvh.prims.size() / 4;
    out.blocks = allocateArray<PrimBlock>(maxBlocks);
    out.info.resize(4 * maxBlocks);
    Collapser c(bvh, out);
    out.root = root.isLeaf() ? c.packLeaf(root) : c.collapse(0);
    out.info.resize(4 * out.blockCount);
    out.info.shrink_to_fit();
    return out;
}

} // namespace mvcl::detail
