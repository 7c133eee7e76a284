#pragma once
/// \file LensContext.h
/// What a lens may know of the view and the scene when it builds its contribution: the camera,
/// the image size, the scene's bounds, where scene space sits in the world, and the layers.
/// Lens::commit() passes the lens's staged context to contribute(); a render session passes its
/// own (the lens's committed values in the session's scene and view), so a lens that depends on
/// the view (LensInfo::dependsOnView) follows the camera without a commit.
///
/// Four spaces:
/// - world space: the model file's coordinates (what users see and type);
/// - bounds space: fractions of the scene's bounding box, 0..1 per axis (a lens whose default
///   must sit inside any model); lengths are fractions of the box's largest side, and vectors
///   are plane normals (they turn with the inverse of the per-axis stretch, so a plane through
///   bounds-space points stays the same plane);
/// - scene space: world − worldOrigin, what the tracer, clip volumes and the camera use;
/// - view space: the camera's frame, origin at the eye, x right, y up, z toward the viewer
///   (the camera looks along −z), in scene units.

#include <mvcl/core/Export.h>

#include <mvcl/core/Bounds3.h>
#include <mvcl/model/CameraDesc.h>
#include <mvcl/model/LayerTable.h>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace mvcl {

struct Scene;

/// The space a point, vector, box or transform property is given in.
enum class PropertySpace : uint8_t {
    World,  ///< the model file's coordinates
    View,   ///< the camera's frame (see LensContext.h): follows the camera
    Bounds, ///< fractions of the scene bounds (see LensContext.h)
};

MVCL_EXPORT const char *propertySpaceName(PropertySpace space);

/// An axis-aligned box in double precision, as a box3 property holds it.
struct Box3d {
    glm::dvec3 min{0.0};
    glm::dvec3 max{0.0};
    bool operator==(const Box3d &other) const = default;
};

struct MVCL_EXPORT LensContext {
    /// Scene space. The default is the camera of a view not known yet.
    CameraDesc camera;
    int imageWidth = 0;  ///< px; 0 when no view is known yet
    int imageHeight = 0;
    Bounds3f sceneBounds; ///< scene space; empty when no scene is known
    /// World position of the scene-space origin (Scene::worldOrigin).
    glm::dvec3 worldOrigin{0.0};
    LayerTable layers;

    /// The scene part (bounds, origin, layers) taken from `scene`; camera and size left as given.
    static LensContext forScene(const Scene &scene);

    glm::vec3 sceneFromWorldPoint(const glm::dvec3 &world) const { return glm::vec3(world - worldOrigin); }
    glm::dvec3 worldFromScenePoint(const glm::vec3 &scene) const { return glm::dvec3(scene) + worldOrigin; }
    /// Columns: the camera's right, up and backward axes in scene space (the rotation
    /// sceneFromView); the same axes as mvcl::Camera::sceneFromCamera().
    glm::mat3 sceneFromViewRotation() const;

    /// A point or direction given in `space`, in scene space. In bounds space a vector is a
    /// plane normal (see above), the same as sceneNormal().
    glm::vec3 scenePoint(const glm::dvec3 &point, PropertySpace space) const;
    glm::vec3 sceneVector(const glm::dvec3 &vector, PropertySpace space) const;
    /// scenePoint() without rounding to float (world and bounds space), for editors whose
    /// values go back into properties.
    glm::dvec3 scenePointInDouble(const glm::dvec3 &point, PropertySpace space) const;
    /// A plane's normal given in `space`, in scene space (not normalised).
    glm::vec3 sceneNormal(const glm::dvec3 &normal, PropertySpace space) const { return sceneVector(normal, space); }
    /// A length (a radius) given in `space`, in scene units.
    double sceneLength(double length, PropertySpace space) const;

    // The inverses, in double, for editors that move a property in scene space (gizmos).
    glm::dvec3 propertyPoint(const glm::dvec3 &scene, PropertySpace space) const;
    glm::dvec3 propertyVector(const glm::dvec3 &scene, PropertySpace space) const;
    double propertyLength(double scene, PropertySpace space) const;
    /// The box in `space` whose scene box is the axis-aligned [sceneMin, sceneMax] (world and
    /// bounds space keep axes; in view space, the box around the turned corners).
    Box3d propertyBox(const glm::dvec3 &sceneMin, const glm::dvec3 &sceneMax, PropertySpace space) const;
    /// The scene-space axis-aligned box that holds `box` given in `space` (in view space the
    /// box turns with the camera, and this is the box around its eight corners).
    Bounds3f sceneBox(const Box3d &box, PropertySpace space) const;
    /// A box property and an optional rotation about its centre in scene space: the box is
    /// converted first (as sceneBox), then turned by `rotation`'s linear part, orthonormalised
    /// (scale and translation do not count). The centre, half sides and the box's axes
    /// (columns) in scene space.
    struct OrientedBox {
        glm::dvec3 center{0.0};
        glm::dvec3 halfExtent{0.0};
        glm::dmat3 axes{1.0};
    };
    OrientedBox sceneOrientedBox(const Box3d &box, const glm::dmat4 &rotation, PropertySpace space) const;
    /// An affine transform (last row 0,0,0,1) given in `space`, as a map of scene space.
    glm::mat4 sceneTransform(const glm::dmat4 &transform, PropertySpace space) const;

    /// Same camera and image size.
    bool sameView(const LensContext &other) const;
    /// Same bounds, origin and layers (ids, names, colours).
    bool sameScene(const LensContext &other) const;
};

} // namespace mvcl
