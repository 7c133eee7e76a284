#pragma once
/// \file Picking.h
/// Picking through the lens: what the primary ray of a pixel hits under the pixel's composed
/// policy, with names a viewer can show. It traces the ray the renderer traces for the pixel's
/// first sample (the pixel centre, moved by the policy's ray shaping) with the policy's primary
/// RayQuery, the one the integrator uses. So a pick agrees with the image: what a lens hides
/// cannot be picked, and the distance is the one a layer lens's `distance` compares with.
///
///     const PolicyMap map = stack.compose(base, width, height);
///     const PickResult p = pick(tracer, camera, map, mouseX, mouseY);
///     if (p.hit) show(p.layerName, p.objectName, p.distance, p.worldPosition);
///
/// A pixel on a feathered lens edge blends several policies; picking uses the dominant one (the
/// largest weight), as PixelProbe does.

#include <mvcl/core/Export.h>

#include <mvcl/lens/PolicyMap.h>
#include <mvcl/tracer/Hit.h>
#include <mvcl/tracer/Ray.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <string>

namespace mvcl {

class Camera;
class Tracer;

/// Plain data, so a viewer may copy it into a panel and keep it after the scene changes.
struct PickResult {
    /// False for a miss, and for a pixel outside the policy map's image.
    bool hit = false;

    // --- the ray (set whenever the pixel is inside the image) ---
    /// Raster position the primary ray goes through, after ray shaping.
    glm::vec2 samplePosition{0.f};
    /// The primary ray in scene space; its direction has unit length.
    Ray ray;
    /// The pixel's dominant policy: index into the map, and its lenses (bit i = stack index i).
    uint16_t policy = 0;
    uint64_t lensSet = 0;

    // --- what it hits (meaningful only when hit) ---
    /// t along the ray, which is the distance from the eye (the layer lens's d).
    float distance = 0.f;
    GeometryKind kind = GeometryKind::Triangle;
    uint32_t geometry = ~0u;  ///< index into Scene::meshes, spheres or planes (by kind)
    uint32_t primitive = ~0u; ///< triangle index within the mesh; 0 for spheres and planes
    int layer = 0;
    std::string layerName; ///< from the scene's LayerTable; empty if the table has no entry
    /// Display name: TriangleMesh::name (node name, else mesh name), or the sphere's or plane's.
    std::string objectName;
    std::string meshName; ///< glTF mesh name; empty for spheres, planes and built-in meshes
    std::string nodeName; ///< glTF node name as written; empty when the node has none
    int sourceNode = -1;  ///< the mesh's TriangleMesh::sourceNode (glTF node index, OBJ group)
    int sourceMesh = -1;  ///< glTF mesh index; -1 for built-in geometry
    uint32_t material = 0; ///< index into Scene::materials
    std::string materialName;
    /// Hit point in scene space (float, as the tracer computes it).
    glm::vec3 scenePosition{0.f};
    /// Hit point in world space: scenePosition + Scene::worldOrigin, in double, so a model far
    /// from the origin reports its real coordinates.
    glm::dvec3 worldPosition{0.0};
    /// Unit normals as the surface is wound (not flipped towards the eye).
    glm::vec3 shadingNormal{0.f, 0.f, 1.f};
    glm::vec3 geometricNormal{0.f, 0.f, 1.f};
    /// True when the ray meets the side the geometric normal points to.
    bool frontFacing = true;
};

/// The primary ray of pixel (x, y) of a width × height image under `policy`: through the pixel
/// centre (x + 0.5, y + 0.5) moved by the policy's ray shaping, i.e. the renderer's sample 0.
MVCL_EXPORT Ray pixelCentreRay(const Camera &camera, const PixelPolicy &policy, int x, int y, int width, int height);

/// What the primary ray of pixel (x, y) hits under the pixel's dominant policy in `map` (whose
/// size is the image's). Const and thread-safe; costs one closest-hit query.
MVCL_EXPORT PickResult pick(const Tracer &tracer, const Camera &camera, const PolicyMap &map, int x, int y);

} // namespace mvcl
