#include <mvcl/model/MeshClosure.h>

#include <mvcl/model/Scene.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <bit>
#include <map>
#include <utility>
#include <vector>

namespace mvcl {

namespace {

struct PositionKey {
    uint32_t x, y, z;
    bool operator==(const PositionKey &) const = default;
};

size_t hashOf(const PositionKey &k) {
    return size_t((uint64_t(k.x) * 0x9e3779b97f4a7c15ull) ^ (uint64_t(k.y) * 0xc2b2ae3d27d4eb4full) ^
                  (uint64_t(k.z) * 0x165667b19e3779f9ull));
}

PositionKey keyOf(const glm::vec3 &p) {
    // +0 and −0 are the same point.
    const auto bits = [](float f) { return f == 0.f ? 0u : std::bit_cast<uint32_t>(f); };
    return {bits(p.x), bits(p.y), bits(p.z)};
}

/// Positions → welded vertex numbers, by exact position: an open-addressing table sized once,
/// so a million-triangle mesh welds without a node per vertex.
class PositionWelder {
public:
    explicit PositionWelder(size_t expected) {
        size_t size = 16;
        while (size < 2 * expected) size *= 2;
        m_slots.assign(size, kEmpty);
        m_keys.reserve(expected);
    }
    uint32_t add(const glm::vec3 &p) {
        const PositionKey key = keyOf(p);
        size_t slot = hashOf(key) & (m_slots.size() - 1);
        while (m_slots[slot] != kEmpty) {
            if (m_keys[m_slots[slot]] == key) return m_slots[slot];
            slot = (slot + 1) & (m_slots.size() - 1);
        }
        m_slots[slot] = uint32_t(m_keys.size());
        m_keys.push_back(key);
        return m_slots[slot];
    }
    size_t count() const { return m_keys.size(); }

private:
    static constexpr uint32_t kEmpty = 0xffffffffu;
    std::vector<uint32_t> m_slots;
    std::vector<PositionKey> m_keys;
};

/// Closed: every undirected edge is used exactly twice, once in each direction. The uses are
/// grouped by their smaller vertex (a counting sort over the triangles, linear, with no list of
/// edges in between: a million triangles make three million uses), and each vertex's few uses
/// are checked among themselves.
bool everyEdgeUsedOnceEachWay(const std::vector<glm::uvec3> &triangles, size_t vertices) {
    if (vertices >= (size_t(1) << 31)) return false; // a use is (high << 1 | upward) in 32 bits
    const auto forEachUse = [&triangles](auto &&use) {
        for (const glm::uvec3 &t : triangles)
            for (const auto &[from, to] : {std::pair{t.x, t.y}, std::pair{t.y, t.z}, std::pair{t.z, t.x}})
                use(std::min(from, to), std::max(from, to), from < to);
    };
    std::vector<uint32_t> start(vertices + 1, 0);
    forEachUse([&start](uint32_t low, uint32_t, bool) { ++start[low + 1]; });
    for (size_t v = 0; v < vertices; ++v) start[v + 1] += start[v];
    std::vector<uint32_t> uses(3 * triangles.size());
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    forEachUse([&](uint32_t low, uint32_t high, bool upward) { uses[fill[low]++] = high << 1 | uint32_t(upward); });
    for (size_t v = 0; v < vertices; ++v) {
        const auto first = uses.begin() + start[v], last = uses.begin() + start[v + 1];
        if ((last - first) % 2 != 0) return false;
        std::sort(first, last);
        for (auto it = first; it != last; it += 2)
            if (it[0] >> 1 != it[1] >> 1 || (it[0] & 1) != 0 || (it[1] & 1) != 1 ||
                (it + 2 != last && it[2] >> 1 == it[0] >> 1))
                return false;
    }
    return true;
}

MeshClosure closureOf(const Scene &scene, const std::vector<size_t> &group) {
    size_t positions = 0, triangles = 0;
    for (const size_t meshIndex : group) {
        positions += scene.meshes[meshIndex].positions.size();
        triangles += scene.meshes[meshIndex].indices.size();
    }
    PositionWelder welder(positions);
    std::vector<glm::uvec3> welded; ///< the triangles over welded vertices, degenerate ones left out
    welded.reserve(triangles);
    double sixTimesVolume = 0.0;
    std::vector<uint32_t> weldedIndex;
    for (const size_t meshIndex : group) {
        const TriangleMesh &mesh = scene.meshes[meshIndex];
        weldedIndex.resize(mesh.positions.size());
        for (size_t i = 0; i < mesh.positions.size(); ++i) weldedIndex[i] = welder.add(mesh.positions[i]);
        for (const glm::uvec3 &tri : mesh.indices) {
            if (tri.x >= weldedIndex.size() || tri.y >= weldedIndex.size() || tri.z >= weldedIndex.size())
                return MeshClosure::Open;
            const uint32_t a = weldedIndex[tri.x], b = weldedIndex[tri.y], c = weldedIndex[tri.z];
            if (a == b || b == c || c == a) continue;
            welded.emplace_back(a, b, c);
            const glm::dvec3 p0(mesh.positions[tri.x]), p1(mesh.positions[tri.y]), p2(mesh.positions[tri.z]);
            sixTimesVolume += glm::dot(p0, glm::cross(p1, p2));
        }
    }
    if (welded.empty() || !everyEdgeUsedOnceEachWay(welded, welder.count())) return MeshClosure::Open;
    if (sixTimesVolume > 0.0) return MeshClosure::Outward;
    if (sixTimesVolume < 0.0) return MeshClosure::Inward;
    return MeshClosure::Open;
}

} // namespace

void recordMeshClosure(Scene &scene) {
    // Group by glTF (node, mesh); built-in geometry (no source) stands alone.
    std::map<std::pair<int, int>, std::vector<size_t>> groups;
    for (size_t i = 0; i < scene.meshes.size(); ++i) {
        const TriangleMesh &mesh = scene.meshes[i];
        if (mesh.sourceNode < 0)
            scene.meshes[i].closure = closureOf(scene, {i});
        else
            groups[{mesh.sourceNode, mesh.sourceMesh}].push_back(i);
    }
    for (const auto &[source, group] : groups) {
        const MeshClosure closure = closureOf(scene, group);
        for (const size_t i : group) scene.meshes[i].closure = closure;
    }
}

} // namespace mvcl
