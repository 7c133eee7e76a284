#pragma once
/// \file Hit.h

#include <cstdint>
#include <limits>

namespace mvcl {

enum class GeometryKind : uint8_t { Triangle = 0, Sphere = 1, Plane = 2 };

/// The result of a closest-hit query. Among hits at exactly equal t the winner is the smallest
/// (layer, kind, geometry, primitive), so images do not depend on BVH layout or thread count.
struct Hit {
    float t = std::numeric_limits<float>::infinity();
    float u = 0.f; ///< barycentric of vertex 1 (triangles)
    float v = 0.f; ///< barycentric of vertex 2 (triangles)
    GeometryKind kind = GeometryKind::Triangle;
    uint8_t layer = 0;
    uint32_t geometry = ~0u;  ///< index into Scene::meshes / spheres / planes
    uint32_t primitive = ~0u; ///< triangle index within the mesh (0 for spheres and planes)

    bool isValid() const { return geometry != ~0u; }
};

/// True if a should win over b (same t order with the deterministic tie-break). Always inlined
/// (GCC, clang): the tracer's kernels, compiled once per instruction set, call it, and must not
/// end up sharing one out-of-line copy.
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
inline bool hitPrecedes(const Hit &a, const Hit &b) {
    if (a.t != b.t) return a.t < b.t;
    if (a.layer != b.layer) return a.layer < b.layer;
    if (a.kind != b.kind) return a.kind < b.kind;
    if (a.geometry != b.geometry) return a.geometry < b.geometry;
    return a.primitive < b.primitive;
}

} // namespace mvcl
