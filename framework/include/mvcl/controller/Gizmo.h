#pragma once
/// \file Gizmo.h
/// 3D handles for a lens's spatial properties, derived from its declarations alone: no plugin
/// writes UI code to get them. Everything here is a pure function of the property values, the
/// scene (a LensContext) and the view (camera and size), so every handle's drag is testable
/// without a window; the Controller keeps the hover and drag state and the viewer only draws the
/// lines and dots of gizmoDrawing().
///
/// Which properties form a gizmo (gizmosOf): every Point3, Vector3, Box3 and Transform in world
/// or bounds space (or whose space a choice picks, PropertyDecl::spaceFrom), grouped by name:
///
///     Box3 `b` (+ Transform `bRotation`)       box: six faces, centre, three rotation rings
///     Point3 `sCenter` + Real `sRadius`        sphere: centre, radius
///     Point3 `pPoint` + Vector3 `pNormal`      plane: point, normal arrow
///     Point3 alone                             point
///     Vector3 alone                            arrow from the centre of the scene bounds
///     Transform alone                          three rotation rings at the centre of the bounds
///
/// A gizmo is offered only while its first property is in use (PropertyDecl::usedWhen).
///
/// Drags (pointer ray = the primary ray through the pointer):
///
///     face        the face moves along its axis (closest point of the ray to the axis line);
///                 the opposite face stays; faces never cross (minimumSize apart), also when
///                 the pointer runs past the axis's vanishing point
///     centre      moves in the camera-facing plane through it; Shift: along the box axis that
///                 looks most like the pointer's motion (a point or plane point: along the
///                 view direction, the vertical pointer motion setting the depth)
///     ring        turns about its axis by the angle the pointer sweeps in the ring's plane; a
///                 ring seen edge-on turns by the pointer's motion along the ring's near side
///     radius      follows the pointer's motion along the direction it was grabbed in (on the
///                 camera-facing plane through the centre); never below minimumSize
///     normal      the arrow's tip follows the pointer on the sphere of the arrow's length

#include <mvcl/core/Export.h>

#include <mvcl/controller/InputEvent.h>
#include <mvcl/lens/LensContext.h>
#include <mvcl/lens/PropertyDecl.h>
#include <mvcl/lens/PropertyValues.h>
#include <mvcl/view/Camera.h>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mvcl {

/// Which properties one gizmo edits (names of the lens's declarations; empty when unused).
struct MVCL_EXPORT GizmoDecl {
    enum class Kind : uint8_t { Box, Sphere, Plane, Point, Arrow, Rings };
    Kind kind = Kind::Point;
    std::string position; ///< Box3 (Box), Point3 (Sphere, Plane, Point); empty for Arrow, Rings
    std::string rotation; ///< Transform (Box, Rings)
    std::string radius;   ///< Real (Sphere), in the centre's space
    std::string normal;   ///< Vector3 (Plane, Arrow)

    /// The property whose space and condition the gizmo follows.
    const std::string &primary() const;
    bool operator==(const GizmoDecl &other) const = default;
};

/// The gizmos of a property table, in table order (see the file comment).
MVCL_EXPORT std::vector<GizmoDecl> gizmosOf(const PropertyTable &table);

/// A gizmo's state in scene space, double precision: what the handles show and drags change.
struct MVCL_EXPORT GizmoShape {
    GizmoDecl decl;
    PropertySpace space = PropertySpace::World; ///< the primary property's resolved space
    PropertySpace normalSpace = PropertySpace::World; ///< the normal's (Plane, Arrow)
    glm::dvec3 center{0.0};     ///< box centre, sphere centre, plane point, point, arrow and ring base
    glm::dvec3 halfExtent{0.0}; ///< Box
    glm::dmat3 axes{1.0};       ///< Box, Rings: columns are the (turned) axes
    double radius = 0.0;        ///< Sphere
    glm::dvec3 normal{0.0, 0.0, 1.0}; ///< Plane, Arrow: unit, scene space
    double size = 1.0;          ///< scene length for arrows and rings that have no size of their own

    /// Reads the gizmo's properties from `values` in `context` (only its scene part is used).
    static GizmoShape read(const GizmoDecl &decl, const PropertyValues &values, const LensContext &context);
    /// The gizmo's properties that give this shape, as (name, canonical text) for
    /// Controller::setLensProperty, converted back into their spaces in `context`.
    std::vector<std::pair<std::string, std::string>> propertyTexts(const LensContext &context) const;
};

/// One grip of a gizmo.
struct MVCL_EXPORT GizmoHandle {
    enum class Kind : uint8_t { Center, Face, Ring, Radius, Normal };
    Kind kind = Kind::Center;
    int gizmo = 0; ///< which shape of the list it came from (Controller::gizmoShapes)
    int axis = 0;  ///< Face, Ring: 0 x, 1 y, 2 z (the gizmo's own axes)
    int side = 1;  ///< Face: +1 or −1
    glm::dvec3 anchor{0.0}; ///< scene space: where it is drawn and grabbed
    glm::vec2 pixel{0.f};   ///< framebuffer pixels

    /// "center", "+x" … "-z", "rotate-x" … "rotate-z", "radius", "normal".
    std::string name() const;
    bool sameGrip(const GizmoHandle &other) const {
        return kind == other.kind && gizmo == other.gizmo && axis == other.axis && side == other.side;
    }
};

/// The view a gizmo is seen in.
struct MVCL_EXPORT GizmoView {
    Camera camera;
    glm::ivec2 viewSize{1, 1};

    /// Framebuffer pixel of a scene point; empty at or behind the eye.
    std::optional<glm::vec2> pixelFromScene(const glm::dvec3 &scene) const;
    /// The primary ray through a framebuffer position: origin and unit direction.
    std::pair<glm::dvec3, glm::dvec3> ray(const glm::vec2 &pixel) const;
    glm::dvec3 forward() const;
    /// Scene length one pixel covers at the depth of `scene`.
    double sceneLengthPerPixel(const glm::dvec3 &scene) const;
};

/// The grips of `shape` that are visible in `view` (in front of the eye; faces and rings that
/// cannot be dragged there — an axis along the view — are left out).
MVCL_EXPORT std::vector<GizmoHandle> gizmoHandles(const GizmoShape &shape, int gizmo, const GizmoView &view);

/// What the viewer draws: line segments and dots in framebuffer pixels.
struct MVCL_EXPORT GizmoDrawing {
    enum class State : uint8_t { Normal, Hovered, Active };
    struct Line {
        std::vector<std::array<glm::vec2, 2>> segments;
        int axis = -1; ///< 0, 1, 2 colour by axis; −1 neutral
        State state = State::Normal;
    };
    struct Dot {
        glm::vec2 position{0.f};
        int axis = -1;
        State state = State::Normal;
    };
    std::vector<Line> lines;
    std::vector<Dot> dots;
};

/// Lines (box edges, rings, sphere outline, arrows) and dots (the handles) of `shape`; the
/// handle equal to `hovered` or `active` (sameGrip) is marked so.
MVCL_EXPORT GizmoDrawing gizmoDrawing(const GizmoShape &shape, int gizmo, const GizmoView &view,
                                      const std::optional<GizmoHandle> &hovered,
                                      const std::optional<GizmoHandle> &active);

/// Framebuffer pixels within which a handle is grabbed (times the content scale): wide enough
/// to hit without aiming.
inline constexpr float kGizmoGrabRadius = 10.f;

/// The handle of `shapes` (gizmo i = shapes[i]) under `pixel`: the nearest dot within
/// `tolerance`, else the nearest ring within it; empty for none.
MVCL_EXPORT std::optional<GizmoHandle> gizmoHandleAt(const std::vector<GizmoShape> &shapes, const GizmoView &view,
                                                     const glm::vec2 &pixel, float tolerance);

/// `start` with `handle` dragged from `pressPixel` to `pixel` (see the file comment).
/// `minimumSize` (scene units) keeps faces apart and radii positive.
MVCL_EXPORT GizmoShape dragGizmo(const GizmoShape &start, const GizmoHandle &handle, const GizmoView &view,
                                 const glm::vec2 &pressPixel, const glm::vec2 &pixel, KeyModifier modifiers,
                                 double minimumSize);

} // namespace mvcl
