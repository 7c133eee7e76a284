#pragma once
/// \file MeshFileMemoryEstimate_p.h
/// Private to MeshFileLoader: what an OBJ, STL or PLY file's geometry will cost once loaded,
/// so that a file over the memory budget is refused before its geometry is read.
///
/// - binary STL and PLY: from the counts in the header, read from the file's first bytes
///   before the rest is read (a PLY's faces count at least one triangle each);
/// - OBJ and ASCII STL: an upper bound from the file's size first (a face line is at least
///   2 bytes a triangle, a vertex line 8 bytes); only when that is over the budget, a
///   pre-count of the whole text (`v` lines and the corners of `f` lines; STL `vertex` lines).
///
/// On top of the loaded geometry (GeometryMemoryEstimate_p.h), the estimate counts what loading
/// holds at its peak: the file's bytes, the reader's positions in double as read and again in
/// world space, and its index triples.

#include "GeometryMemoryEstimate_p.h"

#include <mvcl/model/MeshFileLoader.h>

#include <cstdint>
#include <optional>
#include <span>

namespace mvcl::meshfile {

constexpr double kReaderBytesPerVertex = 24.0 + 24.0;
constexpr double kReaderBytesPerTriangle = 12.0;

/// Bytes of a file's beginning that hold a binary STL's or a PLY's header.
constexpr std::size_t kHeaderProbeBytes = 64 * 1024;

/// From the header counts (binary STL, PLY whose header is within `head`), else nothing.
std::optional<detail::GeometryMemoryEstimate> estimateFromHeader(std::span<const std::uint8_t> head,
                                                                 std::uint64_t fileSize, MeshFormat format);
/// For OBJ and ASCII STL from the whole text: the bound from its size when that fits
/// `budgetBytes`, else a count of its lines.
detail::GeometryMemoryEstimate estimateFromText(std::span<const std::uint8_t> bytes, MeshFormat format,
                                                std::uint64_t budgetBytes);

} // namespace mvcl::meshfile
