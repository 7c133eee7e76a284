#pragma once
/// \file Scene.h
/// The layered model: meshes, spheres, planes, materials, lights, layers and cameras.
/// All geometry is in *scene space* = world space minus `worldOrigin`. Loaders re-centre in double
/// before converting to float so that models far from the world origin keep their precision.

#include <mvcl/core/Export.h>

#include <mvcl/core/Bounds3.h>
#include <mvcl/model/CameraDesc.h>
#include <mvcl/model/LayerContact.h>
#include <mvcl/model/LayerTable.h>
#include <mvcl/model/Light.h>
#include <mvcl/model/Material.h>
#include <mvcl/model/Plane.h>
#include <mvcl/model/Sphere.h>
#include <mvcl/model/Texture.h>
#include <mvcl/model/TriangleMesh.h>

#include <glm/vec3.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace mvcl {

/// What a loader noticed while reading a file; shown by `mvcl-render --info`.
struct LoadReport {
    std::vector<std::string> warnings;
    /// What a loader assumed because the file does not say (up axis, unit), one phrase each.
    std::vector<std::string> assumptions;
    std::size_t degenerateTrianglesDropped = 0;
    std::size_t nonUnitNormalsFixed = 0;
    std::size_t primitivesSkipped = 0; ///< points and lines
    std::size_t texturesDecoded = 0;   ///< images decoded into textures
    std::size_t textureBytes = 0;      ///< memory held by decoded images and their mip chains
    /// Wall time spent inferring layers by containment (0 when nothing was inferred).
    double inferenceMilliseconds = 0.0;
};

struct MVCL_EXPORT Scene {
    std::string name; ///< file path or "builtin:<name>"
    std::vector<TriangleMesh> meshes;
    std::vector<Sphere> spheres;
    std::vector<Plane> planes;
    std::vector<Material> materials; ///< never empty after a loader has run
    std::vector<Texture> textures;   ///< indexed by TextureRef::texture
    std::vector<Light> lights;
    glm::vec3 ambientLight{0.1f};
    glm::vec3 background{0.05f, 0.06f, 0.08f};
    LayerTable layers;
    /// Within this distance an outer layer's hit beats a nearer inner layer's (off by default;
    /// read by the Tracer when it is built).
    LayerContact layerContact;
    std::vector<CameraDesc> cameras;
    /// World-space position of the scene-space origin (double, so far-away models stay exact).
    glm::dvec3 worldOrigin{0.0};
    LoadReport report;

    std::size_t triangleCount() const;
    /// Bounds of meshes and spheres (planes are unbounded and left out).
    Bounds3f bounds() const;
};

} // namespace mvcl
