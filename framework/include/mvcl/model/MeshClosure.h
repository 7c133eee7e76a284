#pragma once
/// \file MeshClosure.h
/// Whether a triangle mesh bounds a solid, which is what lets a clip volume draw a cap where it
/// cuts through the mesh instead of showing a hollow shell.

#include <mvcl/core/Export.h>

#include <cstdint>

namespace mvcl {

struct Scene;
struct TriangleMesh;

/// What a mesh (or the group of meshes one glTF node was split into by material) encloses.
enum class MeshClosure : uint8_t {
    Open,    ///< some edge is not shared by exactly two triangles of opposite winding
    Outward, ///< closed, counter-clockwise faces point out of the solid (positive volume)
    Inward,  ///< closed, but the faces point into the solid (negative volume)
};

/// Sets TriangleMesh::closure of every mesh of `scene`. Meshes made from the same glTF node and
/// mesh are judged together: a solid whose faces use two materials is split into two meshes,
/// each open on its own. Vertices are welded by bit-equal position (glTF splits them at normal
/// and texture seams); triangles with two welded corners equal have no area and are ignored.
/// Closed = every welded edge is used exactly once in each direction, and the enclosed volume
/// is not zero. The glTF loader and the built-in scenes call it; a scene built by hand can too.
MVCL_EXPORT void recordMeshClosure(Scene &scene);

} // namespace mvcl
