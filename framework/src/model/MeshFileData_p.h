#pragma once
/// \file MeshFileData_p.h
/// What a mesh-file reader (OBJ, STL, PLY) hands to MeshFileLoader: parts in the file's own
/// axes and units, in double, already checked (finite, indices in range, counts that fit the
/// file). MeshFileLoader does the rest for every format alike: up axis and unit, normals,
/// degenerate triangles, re-centring, layer rules and closure.

#include <mvcl/core/Error.h>
#include <mvcl/model/Material.h>

#include <glm/vec3.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace mvcl::meshfile {

struct MeshPart {
    std::string name;                 ///< group, object or solid name; empty = the file's stem
    std::vector<glm::dvec3> positions;
    std::vector<glm::dvec3> normals;  ///< empty, or one per position (not yet normalised)
    std::vector<glm::vec3> colors;    ///< empty, or one linear RGB colour per position, 0..1
    std::vector<glm::uvec3> triangles;
    int material = -1;                ///< index into MeshFileData::materials, -1 = default
    /// Parts of one OBJ group split by material bound one solid together (TriangleMesh::sourceNode);
    /// -1: the part stands alone.
    int group = -1;
};

struct MeshFileData {
    std::vector<MeshPart> parts;
    std::vector<Material> materials;
    std::vector<std::string> warnings;
};

/// What every reader is held to.
struct ReadLimits {
    std::size_t maxTriangles = 0;
};

/// Where a reader reads from and whom its errors name.
struct ReadInput {
    std::span<const std::uint8_t> bytes;
    std::string name;               ///< for errors
    std::filesystem::path directory; ///< where an OBJ's material libraries are; empty = none read
    ReadLimits limits;
};

MeshFileData readStl(const ReadInput &input);
MeshFileData readPly(const ReadInput &input);
MeshFileData readObj(const ReadInput &input);

/// Throws the reader's one-line error for `input`'s file.
[[noreturn]] inline void fail(const ReadInput &input, const std::string &problem) { throw Error(input.name, problem); }

inline bool isFinite(const glm::dvec3 &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// Fails unless one more triangle stays within the limit; readers call it as they go, so a
/// hostile count cannot make them allocate first.
inline void checkTriangleCount(const ReadInput &input, std::size_t triangles) {
    if (triangles > input.limits.maxTriangles)
        fail(input, "more than " + std::to_string(input.limits.maxTriangles) + " triangles, more than mvcl loads");
}

} // namespace mvcl::meshfile
