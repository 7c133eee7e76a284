// The 3D handles of Gizmo.h as pure functions: which declarations make which gizmo, the
// projection, the handles and their drags (screen motion → new shape → property texts), seen
// from several sides, with rings edge-on and a face dragged through its opposite.

#include <mvcl/controller/Gizmo.h>

#include <mvcl/lens/PropertyValue.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

using namespace mvcl;

namespace {

constexpr double kPi = 3.14159265358979323846;

GizmoView viewFrom(const glm::vec3 &eye, const glm::vec3 &up = {0.f, 1.f, 0.f}) {
    return GizmoView{Camera::lookAt(eye, glm::vec3(0.f), up, 45.f), {640, 480}};
}

/// The sides the drags are checked from: front, side, top, below and two oblique ones.
std::vector<GizmoView> views() {
    return {viewFrom({0.f, 0.f, 10.f}), viewFrom({10.f, 0.f, 0.f}),     viewFrom({0.f, 10.f, 0.f}, {0.f, 0.f, -1.f}),
            viewFrom({0.f, -10.f, 0.1f}), viewFrom({6.f, 5.f, 7.f}), viewFrom({-7.f, -3.f, -6.f})};
}

GizmoShape boxShape(const glm::dmat3 &axes = glm::dmat3(1.0)) {
    GizmoShape shape;
    shape.decl = {GizmoDecl::Kind::Box, "box", "boxRotation", "", ""};
    shape.center = {0.5, -0.25, 0.0};
    shape.halfExtent = {1.0, 0.75, 0.5};
    shape.axes = axes;
    shape.size = 1.0;
    return shape;
}

std::optional<GizmoHandle> handleNamed(const GizmoShape &shape, const GizmoView &view, const std::string &name) {
    for (const GizmoHandle &handle : gizmoHandles(shape, 0, view))
        if (handle.name() == name) return handle;
    return std::nullopt;
}

/// Drags `name` by `offset` pixels from where it is drawn.
GizmoShape drag(const GizmoShape &shape, const GizmoView &view, const GizmoHandle &handle, const glm::vec2 &offset,
                KeyModifier modifiers = KeyModifier::None) {
    return dragGizmo(shape, handle, view, handle.pixel, handle.pixel + offset, modifiers, 1e-3);
}

/// Screen direction in which the scene direction `a` runs at `p`.
glm::vec2 screenDirection(const GizmoView &view, const glm::dvec3 &p, const glm::dvec3 &a) {
    return glm::normalize(*view.pixelFromScene(p + 0.01 * a) - *view.pixelFromScene(p));
}

bool near(const glm::dvec3 &a, const glm::dvec3 &b, double tolerance = 1e-6) { return glm::length(a - b) < tolerance; }

double faceCoordinate(const GizmoShape &shape, int axis, int side) {
    return glm::dot(shape.center, shape.axes[axis]) + side * shape.halfExtent[axis];
}

PropertyTable clipLikeTable() {
    const auto framed = [](PropertyDecl decl) {
        return decl.withSpaceFrom("frame", {{"scene", PropertySpace::Bounds}, {"world", PropertySpace::World}});
    };
    return {
        PropertyDecl::choice("frame", "scene", {"scene", "world"}, "frame"),
        framed(PropertyDecl::box3("box", {{0.25, 0.25, 0.25}, {0.75, 1.0, 0.5}}, PropertySpace::Bounds, "", "a box")),
        PropertyDecl::transform("boxRotation", glm::dmat4(1.0), PropertySpace::World, "its rotation"),
        framed(PropertyDecl::point3("sphereCenter", {0.5, 0.5, 0.5}, PropertySpace::Bounds, "", "centre")),
        PropertyDecl::real("sphereRadius", 0.25, 0.0, 10.0, "", "radius"),
        framed(PropertyDecl::point3("planePoint", {0.5, 0.5, 0.5}, PropertySpace::Bounds, "", "point")),
        framed(PropertyDecl::vector3("planeNormal", {1.0, 2.0, 0.0}, PropertySpace::Bounds, "", "normal")),
        PropertyDecl::point3("marker", {1.0, 2.0, 3.0}, PropertySpace::World, "", "a lone point"),
        PropertyDecl::point3("anchor", {0.0, 0.0, -1.0}, PropertySpace::View, "", "view space: no gizmo"),
        PropertyDecl::vector3("wind", {0.0, 1.0, 0.0}, PropertySpace::World, "", "a lone vector"),
        PropertyDecl::transform("placement", glm::dmat4(1.0), PropertySpace::World, "a lone transform"),
    };
}

std::vector<PropertyValue> defaultsOf(const PropertyTable &table) {
    std::vector<PropertyValue> values;
    for (const PropertyDecl &decl : table) values.push_back(decl.defaultValue);
    return values;
}

LensContext sceneContext() {
    LensContext context;
    context.sceneBounds = Bounds3f{{-2.f, -1.f, -4.f}, {2.f, 3.f, 4.f}};
    context.worldOrigin = {100.0, 0.0, -50.0};
    return context;
}

} // namespace

TEST(Gizmo, DeclarationsGroupIntoGizmosByTypeAndName) {
    const std::vector<GizmoDecl> gizmos = gizmosOf(clipLikeTable());
    ASSERT_EQ(gizmos.size(), 6u);
    EXPECT_EQ(gizmos[0], (GizmoDecl{GizmoDecl::Kind::Box, "box", "boxRotation", "", ""}));
    EXPECT_EQ(gizmos[1], (GizmoDecl{GizmoDecl::Kind::Sphere, "sphereCenter", "", "sphereRadius", ""}));
    EXPECT_EQ(gizmos[2], (GizmoDecl{GizmoDecl::Kind::Plane, "planePoint", "", "", "planeNormal"}));
    EXPECT_EQ(gizmos[3], (GizmoDecl{GizmoDecl::Kind::Point, "marker", "", "", ""}));
    EXPECT_EQ(gizmos[4], (GizmoDecl{GizmoDecl::Kind::Arrow, "", "", "", "wind"}));
    EXPECT_EQ(gizmos[5], (GizmoDecl{GizmoDecl::Kind::Rings, "", "placement", "", ""}));
}

TEST(Gizmo, ShapeReadsTheDeclaredSpacesAndWritesThemBack) {
    const PropertyTable table = clipLikeTable();
    const std::vector<PropertyValue> values = defaultsOf(table);
    const PropertyValues read(table, values);
    const LensContext context = sceneContext();
    const std::vector<GizmoDecl> gizmos = gizmosOf(table);
    const GizmoShape box = GizmoShape::read(gizmos[0], read, context);
    // Bounds space: x 0.25..0.75 of [-2, 2], y 0.25..1 of [-1, 3], z 0.25..0.5 of [-4, 4].
    EXPECT_TRUE(near(box.center, {0.0, 1.5, -1.0}));
    EXPECT_TRUE(near(box.halfExtent, {1.0, 1.5, 1.0}));
    const GizmoShape sphere = GizmoShape::read(gizmos[1], read, context);
    EXPECT_NEAR(sphere.radius, 0.25 * 8.0, 1e-9); // a fraction of the largest side
    const GizmoShape plane = GizmoShape::read(gizmos[2], read, context);
    // A bounds-space normal (1, 2, 0) over extents (4, 4, 8) is a scene normal along (1, 2, 0).
    EXPECT_TRUE(near(plane.normal, glm::normalize(glm::dvec3(1.0, 2.0, 0.0))));
    const GizmoShape marker = GizmoShape::read(gizmos[3], read, context);
    EXPECT_TRUE(near(marker.center, {-99.0, 2.0, 53.0})); // world minus the origin
    // Written back unchanged, every property of every gizmo parses to its value again.
    for (const GizmoDecl &decl : gizmos)
        for (const auto &[name, text] : GizmoShape::read(decl, read, context).propertyTexts(context)) {
            const PropertyDecl *property = findProperty(table, name);
            ASSERT_NE(property, nullptr) << name;
            const std::vector<double> written = property->parse(text).components();
            const std::vector<double> original = read.value(name).components();
            ASSERT_EQ(written.size(), original.size()) << name;
            for (size_t i = 0; i < written.size(); ++i) {
                if (name == "planeNormal") break; // written normalised; the direction is compared above
                EXPECT_NEAR(written[i], original[i], 1e-6) << name << " " << text;
            }
        }
}

TEST(Gizmo, ProjectionInvertsThePrimaryRay) {
    for (const GizmoView &view : views())
        for (const glm::vec2 pixel : {glm::vec2(0.f, 0.f), glm::vec2(320.f, 240.f), glm::vec2(613.5f, 17.25f)}) {
            const auto [origin, direction] = view.ray(pixel);
            const auto back = view.pixelFromScene(origin + 7.0 * direction);
            ASSERT_TRUE(back.has_value());
            EXPECT_NEAR(back->x, pixel.x, 1e-3);
            EXPECT_NEAR(back->y, pixel.y, 1e-3);
            EXPECT_FALSE(view.pixelFromScene(origin - 1.0 * direction).has_value()) << "behind the eye";
        }
}

TEST(Gizmo, FaceDragMovesOneFaceAlongItsAxisFromEverySide) {
    for (const GizmoView &view : views()) {
        const GizmoShape start = boxShape();
        for (int axis = 0; axis < 3; ++axis)
            for (int side : {1, -1}) {
                const std::string name = std::string(side > 0 ? "+" : "-") + "xyz"[axis];
                const auto handle = handleNamed(start, view, name);
                if (std::abs(glm::dot(start.axes[axis], view.forward())) > 0.95) {
                    EXPECT_FALSE(handle) << name << ": an axis along the view offers no face";
                    continue;
                }
                ASSERT_TRUE(handle) << name;
                // 30 px outward along the axis's screen image.
                const glm::vec2 outward = float(side) * screenDirection(view, handle->anchor, start.axes[axis]);
                const GizmoShape moved = drag(start, view, *handle, 30.f * outward);
                EXPECT_GT(side * (faceCoordinate(moved, axis, side) - faceCoordinate(start, axis, side)), 0.0) << name;
                EXPECT_NEAR(faceCoordinate(moved, axis, -side), faceCoordinate(start, axis, -side), 1e-9)
                    << name << ": the opposite face stays";
                for (int other = 0; other < 3; ++other)
                    if (other != axis) {
                        EXPECT_NEAR(moved.halfExtent[other], start.halfExtent[other], 1e-12);
                        EXPECT_NEAR(moved.center[other], start.center[other], 1e-12);
                    }
                // The face follows the pointer: its new centre is drawn under the pointer's
                // position projected on the axis's screen line.
                const glm::dvec3 faceCenter = moved.center + double(side) * moved.halfExtent[axis] * moved.axes[axis];
                const glm::vec2 drawn = *view.pixelFromScene(faceCenter);
                EXPECT_NEAR(glm::dot(drawn - handle->pixel, outward), 30.f, 0.5f) << name;
            }
    }
}

TEST(Gizmo, FaceDraggedThroughItsOppositeStopsBeforeIt) {
    for (const GizmoView &view : views()) {
        const GizmoShape start = boxShape();
        const auto handle = handleNamed(start, view, "+x");
        if (!handle) continue;
        const glm::vec2 inward = -screenDirection(view, handle->anchor, start.axes[0]);
        const GizmoShape moved = drag(start, view, *handle, 2000.f * inward);
        EXPECT_NEAR(faceCoordinate(moved, 0, -1), faceCoordinate(start, 0, -1), 1e-9);
        EXPECT_NEAR(2.0 * moved.halfExtent.x, 1e-3, 1e-9) << "the faces stay minimumSize apart";
        EXPECT_LT(faceCoordinate(moved, 0, -1), faceCoordinate(moved, 0, 1));
    }
}

TEST(Gizmo, FaceOfATurnedBoxMovesAlongTheTurnedAxis) {
    const glm::dmat3 turned = glm::dmat3(glm::dvec3(std::cos(0.5), std::sin(0.5), 0.0),
                                         glm::dvec3(-std::sin(0.5), std::cos(0.5), 0.0), glm::dvec3(0, 0, 1));
    const GizmoShape start = boxShape(turned);
    const GizmoView view = viewFrom({6.f, 5.f, 7.f});
    const auto handle = handleNamed(start, view, "+x");
    ASSERT_TRUE(handle);
    const GizmoShape moved = drag(start, view, *handle, 25.f * screenDirection(view, handle->anchor, turned[0]));
    const glm::dvec3 shift = moved.center - start.center;
    EXPECT_NEAR(glm::length(glm::cross(shift, turned[0])), 0.0, 1e-9) << "the centre moves along the turned x";
    EXPECT_NEAR(faceCoordinate(moved, 0, -1), faceCoordinate(start, 0, -1), 1e-9);
}

TEST(Gizmo, CenterDragFollowsThePointerInTheViewPlane) {
    for (const GizmoView &view : views()) {
        const GizmoShape start = boxShape();
        const auto handle = handleNamed(start, view, "center");
        ASSERT_TRUE(handle);
        const GizmoShape moved = drag(start, view, *handle, {40.f, -25.f});
        const glm::vec2 drawn = *view.pixelFromScene(moved.center);
        EXPECT_NEAR(drawn.x, handle->pixel.x + 40.f, 0.01f);
        EXPECT_NEAR(drawn.y, handle->pixel.y - 25.f, 0.01f);
        EXPECT_NEAR(glm::dot(moved.center - start.center, view.forward()), 0.0, 1e-9) << "same depth";
        EXPECT_EQ(moved.halfExtent, start.halfExtent);
    }
}

TEST(Gizmo, ShiftCenterDragMovesABoxAlongOneAxis) {
    const GizmoView view = viewFrom({6.f, 5.f, 7.f});
    const GizmoShape start = boxShape();
    const auto handle = handleNamed(start, view, "center");
    ASSERT_TRUE(handle);
    const glm::vec2 alongY = screenDirection(view, start.center, {0.0, 1.0, 0.0});
    const GizmoShape moved = drag(start, view, *handle, 30.f * alongY + glm::vec2(1.f, 0.f), KeyModifier::Shift);
    const glm::dvec3 shift = moved.center - start.center;
    EXPECT_GT(shift.y, 0.0);
    EXPECT_EQ(shift.x, 0.0);
    EXPECT_EQ(shift.z, 0.0);
}

TEST(Gizmo, ShiftPointDragMovesAlongTheViewDirection) {
    GizmoShape point;
    point.decl = {GizmoDecl::Kind::Point, "marker", "", "", ""};
    point.center = {0.3, 0.2, 0.1};
    for (const GizmoView &view : views()) {
        const auto handle = handleNamed(point, view, "center");
        ASSERT_TRUE(handle);
        const GizmoShape away = drag(point, view, *handle, {0.f, -20.f}, KeyModifier::Shift);
        const glm::dvec3 shift = away.center - point.center;
        EXPECT_GT(glm::dot(shift, view.forward()), 0.0) << "pointer up moves it away";
        EXPECT_NEAR(glm::length(glm::cross(shift, view.forward())), 0.0, 1e-9);
    }
}

TEST(Gizmo, RingTurnsTheBoxAboutItsAxisBySweptAngle) {
    // Seen from +z, the z ring faces the viewer: a quarter turn of the pointer about the centre
    // turns the box a quarter turn.
    const GizmoView view = viewFrom({0.f, 0.f, 10.f});
    GizmoShape start = boxShape();
    start.center = {0.0, 0.0, 0.0};
    const auto handle = handleNamed(start, view, "rotate-z");
    ASSERT_TRUE(handle);
    const glm::vec2 centre = *view.pixelFromScene(start.center);
    const glm::vec2 radial = handle->pixel - centre;
    const glm::vec2 quarter(-radial.y, radial.x); // 90° on screen (y down: clockwise seen)
    const GizmoShape turned = dragGizmo(start, *handle, view, handle->pixel, centre + quarter, KeyModifier::None, 1e-3);
    EXPECT_TRUE(near(turned.axes[2], start.axes[2])) << "the ring's own axis stays";
    const double angle = std::atan2(turned.axes[0].y, turned.axes[0].x);
    EXPECT_NEAR(std::abs(angle), kPi / 2, 1e-3);
    EXPECT_LT(angle, 0.0) << "clockwise on screen with y down is clockwise about +z seen from +z";
    EXPECT_EQ(turned.center, start.center);
    EXPECT_EQ(turned.halfExtent, start.halfExtent);
}

TEST(Gizmo, RingSeenEdgeOnStillTurnsAndTurnsBack) {
    // Seen from +z, the x ring is a vertical line: the pointer is on its camera-facing plane.
    const GizmoView view = viewFrom({0.f, 0.f, 10.f});
    GizmoShape start = boxShape();
    start.center = {0.0, 0.0, 0.0};
    const auto handle = handleNamed(start, view, "rotate-x");
    ASSERT_TRUE(handle);
    for (const glm::vec2 offset : {glm::vec2(0.f, 30.f), glm::vec2(0.f, -30.f)}) {
        const GizmoShape turned = drag(start, view, *handle, offset);
        const double angle = std::atan2(turned.axes[1].z, turned.axes[1].y);
        EXPECT_GT(std::abs(angle), 0.05) << "a drag along the line turns the ring";
        EXPECT_TRUE(near(turned.axes[0], start.axes[0]));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(glm::length(turned.axes[c]), 1.0, 1e-12);
        // Back where it started: the identity again.
        const GizmoShape back = dragGizmo(turned, *handle, view, handle->pixel + offset, handle->pixel,
                                          KeyModifier::None, 1e-3);
        EXPECT_TRUE(near(back.axes[1], start.axes[1], 1e-9));
    }
    // Up and down turn opposite ways.
    const double up = std::atan2(drag(start, view, *handle, {0.f, -30.f}).axes[1].z, 1.0);
    const double down = std::atan2(drag(start, view, *handle, {0.f, 30.f}).axes[1].z, 1.0);
    EXPECT_LT(up * down, 0.0);
}

TEST(Gizmo, RadiusFollowsThePointerAndStaysPositive) {
    GizmoShape sphere;
    sphere.decl = {GizmoDecl::Kind::Sphere, "sphereCenter", "", "sphereRadius", ""};
    sphere.center = {0.2, 0.1, -0.3};
    sphere.radius = 1.0;
    for (const GizmoView &view : views()) {
        const auto handle = handleNamed(sphere, view, "radius");
        ASSERT_TRUE(handle);
        const GizmoShape larger = drag(sphere, view, *handle, {20.f, 0.f}); // the handle sits to the right
        EXPECT_NEAR(larger.radius - sphere.radius, 20.0 * view.sceneLengthPerPixel(sphere.center), 1e-6);
        EXPECT_EQ(larger.center, sphere.center);
        EXPECT_NEAR(drag(sphere, view, *handle, {-5000.f, 0.f}).radius, 1e-3, 1e-12) << "never below minimumSize";
    }
}

TEST(Gizmo, NormalTipFollowsThePointerOnItsSphere) {
    GizmoShape plane;
    plane.decl = {GizmoDecl::Kind::Plane, "planePoint", "", "", "planeNormal"};
    plane.center = {0.0, 0.0, 0.0};
    plane.normal = {1.0, 0.0, 0.0};
    plane.size = 2.0;
    for (const GizmoView &view : views()) {
        const auto handle = handleNamed(plane, view, "normal");
        if (!handle) continue;
        const GizmoShape turned = drag(plane, view, *handle, {-10.f, -15.f});
        EXPECT_NEAR(glm::length(turned.normal), 1.0, 1e-12);
        EXPECT_EQ(turned.center, plane.center);
        const glm::vec2 tip = *view.pixelFromScene(turned.center + turned.size * turned.normal);
        EXPECT_NEAR(glm::length(tip - (handle->pixel + glm::vec2(-10.f, -15.f))), 0.f, 0.05f);
    }
}

TEST(Gizmo, HitTestGrabsWithinTenPixelsAndPrefersDots) {
    const GizmoView view = viewFrom({6.f, 5.f, 7.f});
    const std::vector<GizmoShape> shapes{boxShape()};
    const auto face = handleNamed(shapes[0], view, "+y");
    ASSERT_TRUE(face);
    EXPECT_GE(kGizmoGrabRadius, 8.f);
    const auto near9 = gizmoHandleAt(shapes, view, face->pixel + glm::vec2(9.f, 0.f), kGizmoGrabRadius);
    ASSERT_TRUE(near9);
    EXPECT_EQ(near9->name(), "+y");
    // Far from every dot and ring: nothing.
    EXPECT_FALSE(gizmoHandleAt(shapes, view, {2.f, 2.f}, kGizmoGrabRadius));
    // On a ring away from the dots: the ring.
    const auto ringHandle = handleNamed(shapes[0], view, "rotate-y");
    ASSERT_TRUE(ringHandle);
    const GizmoDrawing drawing = gizmoDrawing(shapes[0], 0, view, std::nullopt, std::nullopt);
    int rings = 0;
    for (const GizmoDrawing::Line &line : drawing.lines)
        if (line.axis == 1) {
            ++rings;
            // A point on this ring's drawn segments, at most the tolerance from any dot?
            for (const auto &segment : line.segments) {
                const glm::vec2 middle = 0.5f * (segment[0] + segment[1]);
                bool nearDot = false;
                for (const GizmoHandle &h : gizmoHandles(shapes[0], 0, view))
                    nearDot = nearDot || glm::length(h.pixel - middle) < kGizmoGrabRadius;
                if (nearDot) continue;
                const auto hit = gizmoHandleAt(shapes, view, middle + glm::vec2(0.f, 0.f), kGizmoGrabRadius);
                ASSERT_TRUE(hit);
                EXPECT_EQ(hit->kind, GizmoHandle::Kind::Ring);
                break;
            }
        }
    EXPECT_EQ(rings, 1);
}

TEST(Gizmo, DrawingMarksTheHoveredAndActiveHandles) {
    const GizmoView view = viewFrom({6.f, 5.f, 7.f});
    const GizmoShape shape = boxShape();
    const auto face = handleNamed(shape, view, "-z");
    const auto ring = handleNamed(shape, view, "rotate-x");
    ASSERT_TRUE(face && ring);
    const GizmoDrawing drawing = gizmoDrawing(shape, 0, view, face, ring);
    int hovered = 0, active = 0;
    for (const GizmoDrawing::Dot &dot : drawing.dots) {
        hovered += dot.state == GizmoDrawing::State::Hovered;
        active += dot.state == GizmoDrawing::State::Active;
    }
    EXPECT_EQ(hovered, 1);
    EXPECT_EQ(active, 1);
    bool activeRing = false;
    for (const GizmoDrawing::Line &line : drawing.lines)
        activeRing = activeRing || (line.axis == 0 && line.state == GizmoDrawing::State::Active);
    EXPECT_TRUE(activeRing);
    EXPECT_EQ(drawing.lines.front().segments.size(), 12u) << "a box's twelve edges";
}

TEST(Gizmo, BoxDragWritesPropertiesThatReadBackAsTheDraggedShape) {
    const PropertyTable table = clipLikeTable();
    const std::vector<PropertyValue> values = defaultsOf(table);
    const LensContext context = sceneContext();
    const GizmoDecl decl = gizmosOf(table)[0];
    const GizmoShape start = GizmoShape::read(decl, PropertyValues(table, values), context);
    const GizmoView view = viewFrom({6.f, 5.f, 7.f});
    GizmoShape moved = drag(start, view, *handleNamed(start, view, "+x"), {25.f, 5.f});
    moved = drag(moved, view, *handleNamed(moved, view, "rotate-y"), {-20.f, 30.f});
    std::vector<PropertyValue> written = values;
    for (const auto &property : moved.propertyTexts(context)) { // not a binding: the lambda captures it
        const std::string &name = property.first;
        const auto at = std::ranges::find_if(table, [&](const PropertyDecl &d) { return d.name == name; });
        written[size_t(at - table.begin())] = at->parse(property.second);
    }
    const GizmoShape back = GizmoShape::read(decl, PropertyValues(table, written), context);
    EXPECT_TRUE(near(back.center, moved.center, 1e-5));
    EXPECT_TRUE(near(back.halfExtent, moved.halfExtent, 1e-5));
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(near(back.axes[c], moved.axes[c], 1e-9));
}
