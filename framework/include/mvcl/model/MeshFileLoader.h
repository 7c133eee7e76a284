#pragma once
/// \file MeshFileLoader.h
/// Mesh files that carry geometry and little else: Wavefront OBJ (+ MTL), STL (binary and
/// ASCII) and PLY (ASCII, binary little- and big-endian) → Scene. Every reader validates what it
/// reads as the glTF loader does: counts against the file's size, indices against the vertex
/// count, finite coordinates, the same limits on bytes and triangles.
///
/// None of these formats says which axis is up or what its unit is; MeshFileOptions says what to
/// assume, and Scene::report.assumptions records it so that a summary can print it.

#include <mvcl/core/Export.h>

#include <mvcl/model/LayerRules.h>
#include <mvcl/model/Scene.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace mvcl {

enum class MeshFormat : uint8_t { Obj, Stl, Ply };

/// The axis a file treats as up; mvcl's world is y-up (as glTF's).
enum class UpAxis : uint8_t { Y, Z };

/// The length unit of a file's coordinates; mvcl's world unit is the metre (as glTF's).
enum class LengthUnit : uint8_t { Millimetre, Centimetre, Metre, Inch };

struct MeshFileOptions {
    /// Rules applied to the meshes by name (OBJ group or object, STL solid name).
    LayerRules layerRules;
    /// Up axis of the file; unset = y, and the report says it was assumed.
    std::optional<UpAxis> upAxis;
    /// Unit of the file; unset = metre, and the report says it was assumed.
    std::optional<LengthUnit> unit;
    /// Files larger than this are rejected before reading (bytes).
    std::uint64_t maxFileBytes = 1ull << 31;
    /// Files with more triangles than this are rejected (after polygons are split).
    std::size_t maxTriangles = std::size_t(1) << 27;
    /// A file whose geometry would need more memory than this (meshes, the tracer's BVH and
    /// what loading holds at its peak; estimated from a binary STL's or a PLY's header before
    /// the rest of the file is read, from the text of an OBJ or ASCII STL) is refused with the
    /// estimate in the error. 0 = no limit.
    std::uint64_t maxGeometryBytes = 0;
};

/// Loads an OBJ, STL or PLY file as `format`. Meshes get their layer from the rules; the rest
/// stay LayerSource::Unassigned for SceneLoader's containment inference.
/// Throws mvcl::Error naming the file and the problem for anything invalid.
MVCL_EXPORT Scene loadMeshFile(const std::filesystem::path &path, MeshFormat format,
                               const MeshFileOptions &options = {});

/// Same, from memory (fuzzing, tests). `name` is used in error messages and as the name of
/// meshes that have none; an OBJ's material libraries are not read.
MVCL_EXPORT Scene loadMeshFileFromMemory(std::span<const std::uint8_t> bytes, const std::string &name,
                                         MeshFormat format, const MeshFileOptions &options = {});

/// "y" or "z"; std::nullopt for anything else.
MVCL_EXPORT std::optional<UpAxis> upAxisFromName(std::string_view name);
/// "mm", "cm", "m" or "in"; std::nullopt for anything else.
MVCL_EXPORT std::optional<LengthUnit> lengthUnitFromName(std::string_view name);
MVCL_EXPORT const char *upAxisName(UpAxis axis);
MVCL_EXPORT const char *lengthUnitName(LengthUnit unit);
/// Metres per unit.
MVCL_EXPORT double metresPer(LengthUnit unit);

} // namespace mvcl
