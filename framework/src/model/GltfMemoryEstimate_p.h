#pragma once
/// \file GltfMemoryEstimate_p.h
/// Private to the glTF loader: what a validated model's geometry will cost once loaded (meshes in
/// world space, one copy per instance, and the tracer's BVH over them), from the accessors'
/// counts alone, so that a model over the memory budget is refused before any of it is read.

#include "GltfValidator_p.h"

#include <cstdint>

namespace mvcl::gltf {

struct GltfMemoryEstimate {
    double triangles = 0.0; ///< over every instance (double: counts times instances may exceed 64 bits)
    double vertices = 0.0;
    double bytes = 0.0;
};

/// Bytes per triangle: the BVH with its primitive blocks (77–91 measured on real models,
/// docs/benchmarks.md) plus the build's scratch, and the mesh's index triple.
constexpr double kEstimatedBytesPerTriangle = 96.0 + 48.0 + 12.0;
/// Bytes per vertex: position, normal, two texture coordinates and a tangent.
constexpr double kEstimatedBytesPerVertex = 12.0 + 12.0 + 16.0 + 16.0;

GltfMemoryEstimate estimateGeometryMemory(const GltfContext &context, const GltfValidator &validator);

} // namespace mvcl::gltf
