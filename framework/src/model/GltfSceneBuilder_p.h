#pragma once
/// \file GltfSceneBuilder_p.h
/// Private to the glTF loader: turns a validated tinygltf model into a mvcl::Scene (node
/// transforms in double, re-centring, triangulation, normals, materials, lights, cameras, layers).

#include "GltfAccessorReader_p.h"
#include "GltfValidator_p.h"

#include <mvcl/model/GltfLoader.h>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <vector>

namespace mvcl::gltf {

class GltfSceneBuilder {
public:
    GltfSceneBuilder(GltfContext &context, const GltfValidator &validator, const GltfLoadOptions &options,
                     Scene &scene);

    void build();

private:
    /// One mesh primitive decoded once in its own (object) space and shared by every instance.
    struct DecodedPrimitive {
        bool decoded = false;
        bool usable = false;
        std::vector<glm::vec3> positions;
        std::vector<glm::vec3> normals; ///< empty or unit, one per position
        std::vector<glm::uvec3> triangles; ///< non-degenerate, counter-clockwise
        std::vector<glm::vec2> texcoords0, texcoords1; ///< empty or one per position
        std::vector<glm::vec4> tangents; ///< empty or one per position (read, or generated for normal maps)
        std::size_t degenerate = 0;
    };
    /// A TriangleMesh under construction; world positions stay in double until re-centring.
    struct PendingMesh {
        TriangleMesh mesh;
        std::vector<glm::dvec3> world;
    };
    struct PendingCamera {
        CameraDesc desc;
        glm::dvec3 eye, forward, up;
    };
    struct PendingLight {
        Light light;
        glm::dvec3 position;
    };

    uint32_t defaultMaterial();
    glm::dmat4 localTransform(int node);
    void traverse();
    void instantiateMesh(int node, const glm::dmat4 &world);
    void addCamera(int node, const glm::dmat4 &world);
    void addLight(int node, const glm::dmat4 &world);
    const DecodedPrimitive &decode(int mesh, int primitive);
    void decodeNormals(int accessor, DecodedPrimitive &out);
    void decodeTextureAttributes(const tinygltf::Primitive &prim, const std::string &where, DecodedPrimitive &out);
    template <typename T>
    static void appendAttribute(std::vector<T> &mesh, const std::vector<T> &primitive, std::size_t base,
                                std::size_t count);
    std::optional<int> extrasLayer(const tinygltf::Value &extras, const std::string &owner) const;
    void assignLayer(TriangleMesh &mesh, int node);
    void finish();

    GltfContext &m_context;
    const tinygltf::Model &m_model;
    const GltfValidator &m_validator;
    GltfAccessorReader m_reader;
    const GltfLoadOptions &m_options;
    Scene &m_scene;

    std::optional<uint32_t> m_defaultMaterial;
    std::vector<std::vector<DecodedPrimitive>> m_decoded; // [mesh][primitive]
    std::vector<PendingMesh> m_pending;
    std::vector<PendingCamera> m_cameras;
    std::vector<PendingLight> m_lights;
    std::size_t m_triangles = 0;
};

} // namespace mvcl::gltf
