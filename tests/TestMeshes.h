#pragma once
// Meshes that tests build by hand.

#include <mvcl/model/TriangleMesh.h>

#include <array>

namespace mvcl::test {

/// An axis-aligned box with four vertices of its own per face (split as glTF splits them at
/// normal seams), counter-clockwise seen from outside: a closed, outward mesh.
inline TriangleMesh splitFaceBox(const glm::vec3 &lo, const glm::vec3 &hi) {
    TriangleMesh mesh;
    const auto corner = [&](int i) { return glm::vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z); };
    const std::array<std::array<int, 4>, 6> faces{{{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                                   {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}};
    for (const auto &face : faces) {
        const uint32_t base = uint32_t(mesh.positions.size());
        for (const int c : face) mesh.positions.push_back(corner(c));
        mesh.indices.push_back({base, base + 1, base + 2});
        mesh.indices.push_back({base, base + 2, base + 3});
    }
    return mesh;
}

} // namespace mvcl::test
