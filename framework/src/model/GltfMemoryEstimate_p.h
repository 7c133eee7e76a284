#pragma once
/// \file GltfMemoryEstimate_p.h
/// Private to the glTF loader: what a validated model's geometry will cost once loaded (meshes in
/// world space, one copy per instance, and the tracer's BVH over them), from the accessors'
/// counts alone, so that a model over the memory budget is refused before any of it is read.

#include "GeometryMemoryEstimate_p.h"
#include "GltfValidator_p.h"

namespace mvcl::gltf {

/// Triangles and vertices over every instance.
using GltfMemoryEstimate = detail::GeometryMemoryEstimate;
using detail::kEstimatedBytesPerTriangle;
using detail::kEstimatedBytesPerVertex;

GltfMemoryEstimate estimateGeometryMemory(const GltfContext &context, const GltfValidator &validator);

} // namespace mvcl::gltf
