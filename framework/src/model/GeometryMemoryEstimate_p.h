#pragma once
/// \file GeometryMemoryEstimate_p.h
/// Private to the model readers: what a model's geometry will cost once loaded (the meshes and
/// the tracer's BVH over them), and the one refusal every reader gives when that is over the
/// memory budget, before any of the geometry is read.

#include <cstdint>
#include <string>

namespace mvcl::detail {

/// Bytes per triangle: the BVH with its primitive blocks (77–91 measured on real models,
/// docs/benchmarks.md) plus the build's scratch, and the mesh's index triple.
constexpr double kEstimatedBytesPerTriangle = 96.0 + 48.0 + 12.0;
/// Bytes per vertex: position, normal, two texture coordinates and a tangent.
constexpr double kEstimatedBytesPerVertex = 12.0 + 12.0 + 16.0 + 16.0;

struct GeometryMemoryEstimate {
    double triangles = 0.0; ///< double: counts times instances may exceed 64 bits
    double vertices = 0.0;
    double bytes = 0.0;
};

/// "123 MiB"
std::string mebibytes(double bytes);

/// Throws mvcl::Error("", "its geometry would need about … (T triangles, V vertices: `what`),
/// more than the memory budget of … MiB; refused before loading it") when `estimate.bytes` is
/// over `budgetBytes`; the caller names the file.
void refuseOverBudget(const GeometryMemoryEstimate &estimate, std::uint64_t budgetBytes,
                      const std::string &what = "meshes and BVH");

} // namespace mvcl::detail
