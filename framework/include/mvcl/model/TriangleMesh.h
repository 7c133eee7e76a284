#pragma once
/// \file TriangleMesh.h
/// A triangle mesh as in the paper: a vertex list plus a triangle index list, in scene space
/// (node transforms already applied, in double, then re-centred on Scene::worldFromScene).

#include <mvcl/model/MeshClosure.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace mvcl {

/// Where a mesh's layer came from, in order of precedence.
enum class LayerSource : uint8_t {
    Unassigned, ///< not yet decided; SceneLoader runs containment inference on these
    Builtin,    ///< set by a built-in scene
    Extras,     ///< glTF `extras.layer` on the node or the mesh
    Rule,       ///< a user rule (name glob → layer)
    Inferred,   ///< automatic inference by containment
    File,       ///< one file of several loaded as layers: the file's place in the list
};

struct TriangleMesh {
    std::string name;      ///< node name, or mesh name when the node has none (for display)
    std::string nodeName;  ///< glTF node name as written (may be empty; empty for built-ins)
    std::string meshName;  ///< glTF mesh name (may be empty)
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;  ///< empty, or one unit normal per position
    std::vector<glm::uvec3> indices; ///< triangles, counter-clockwise = front
    /// Texture coordinates (glTF TEXCOORD_0 and TEXCOORD_1): empty, or one per position.
    std::vector<glm::vec2> texcoords0;
    std::vector<glm::vec2> texcoords1;
    /// Tangent-space frames for normal maps: empty, or one per position, xyz unit and
    /// perpendicular to the normal, w = ±1 the handedness (bitangent = w · normal × tangent).
    std::vector<glm::vec4> tangents;
    uint32_t material = 0;           ///< index into Scene::materials
    int layer = 0;
    LayerSource layerSource = LayerSource::Unassigned;
    /// For LayerSource::Inferred, how clearly the mesh's part was seen from outside when it was
    /// peeled, 0..1: 1 = none of its samples enclosed, 0 = at the threshold (or peeled only
    /// because everything left enclosed everything else). 1 for the other sources.
    float layerConfidence = 1.f;
    /// Whether the mesh bounds a solid (see recordMeshClosure): clip volumes cap closed meshes.
    MeshClosure closure = MeshClosure::Open;
    /// glTF node and mesh index; an OBJ group's index and 0 (its meshes, one per material, bound
    /// one solid); -1 for built-in geometry and STL and PLY meshes. Meshes with the same pair
    /// form one solid (closure, layer inference), within one file.
    int sourceNode = -1;
    int sourceMesh = -1;
};

} // namespace mvcl
