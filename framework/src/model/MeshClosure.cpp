#include <mvcl/model/MeshClosure.h>

#include <mvcl/model/Scene.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <bit>
#include <map>
#include <unordered_map>
#include <utility>
#include <vector>

namespace mvcl {

namespace {

struct PositionKey {
    uint32_t x, y, z;
    bool operator==(const PositionKey &) const = default;
};

struct PositionKeyHash {
    size_t operator()(const PositionKey &k) const {
        return size_t((uint64_t(k.x) * 0x9e3779b97f4a7c15ull) ^ (uint64_t(k.y) * 0xc2b2ae3d27d4eb4full) ^
                      (uint64_t(k.z) * 0x165667b19e3779f9ull));
    }
};

PositionKey keyOf(const glm::vec3 &p) {
    // +0 and −0 are the same point.
    const auto bits = [](float f) { return f == 0.f ? 0u : std::bit_cast<uint32_t>(f); };
    return {bits(p.x), bits(p.y), bits(p.z)};
}

/// The closure of the union of `group`'s meshes.
MeshClosure closureOf(const Scene &scene, const std::vector<size_t> &group) {
    std::unordered_map<PositionKey, uint32_t, PositionKeyHash> welded;
    // Directed welded edge (from, to) → how often it is used; an undirected edge is closed when
    // both directions are used exactly once.
    std::unordered_map<uint64_t, uint32_t> directedUses;
    double sixTimesVolume = 0.0;
    for (const size_t meshIndex : group) {
        const TriangleMesh &mesh = scene.meshes[meshIndex];
        std::vector<uint32_t> weldedIndex(mesh.positions.size());
        for (size_t i = 0; i < mesh.positions.size(); ++i)
            weldedIndex[i] = welded.try_emplace(keyOf(mesh.positions[i]), uint32_t(welded.size())).first->second;
        for (const glm::uvec3 &tri : mesh.indices) {
            if (tri.x >= weldedIndex.size() || tri.y >= weldedIndex.size() || tri.z >= weldedIndex.size())
                return MeshClosure::Open;
            const uint32_t a = weldedIndex[tri.x], b = weldedIndex[tri.y], c = weldedIndex[tri.z];
            if (a == b || b == c || c == a) continue;
            for (const auto &[from, to] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}})
                ++directedUses[uint64_t(from) << 32 | to];
            const glm::dvec3 p0(mesh.positions[tri.x]), p1(mesh.positions[tri.y]), p2(mesh.positions[tri.z]);
            sixTimesVolume += glm::dot(p0, glm::cross(p1, p2));
        }
    }
    if (directedUses.empty()) return MeshClosure::Open;
    for (const auto &[edge, uses] : directedUses) {
        const uint64_t reversed = (edge << 32) | (edge >> 32);
        const auto it = directedUses.find(reversed);
        if (uses != 1 || it == directedUses.end() || it->second != 1) return MeshClosure::Open;
    }
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
