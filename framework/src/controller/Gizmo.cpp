// Gizmo geometry: projection, handles, what the viewer draws, hit tests and drags (Gizmo.h).

#include <mvcl/controller/Gizmo.h>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mvcl {

namespace {

constexpr int kRingSegments = 64;
/// A face whose axis is this near the view direction cannot be dragged along it (the pointer
/// ray runs along the axis): its handle is not offered.
constexpr double kAxisAlongView = 0.95;
/// A ring whose plane the pointer ray meets at a cosine below this is dragged as seen edge-on.
constexpr double kRingEdgeOn = 0.2;

double tanHalfFov(const Camera &camera) {
    return std::tan(double(camera.verticalFovDegrees()) * 3.14159265358979323846 / 360.0);
}

/// Where the line P + t·a comes closest to the ray o + u·d (both directions unit); empty when
/// they are (nearly) parallel.
std::optional<double> closestOnLine(const glm::dvec3 &P, const glm::dvec3 &a, const glm::dvec3 &o, const glm::dvec3 &d) {
    const glm::dvec3 w = P - o;
    const double b = glm::dot(a, d), denominator = 1.0 - b * b;
    if (!(denominator > 1e-6)) return std::nullopt;
    return (b * glm::dot(d, w) - glm::dot(a, w)) / denominator;
}

/// The ray's hit on the plane through P with normal n; empty when parallel or behind.
std::optional<glm::dvec3> onPlane(const glm::dvec3 &P, const glm::dvec3 &n, const glm::dvec3 &o, const glm::dvec3 &d) {
    const double along = glm::dot(n, d);
    if (std::abs(along) < 1e-9) return std::nullopt;
    const double t = glm::dot(n, P - o) / along;
    if (!(t > 0.0)) return std::nullopt;
    return o + t * d;
}

/// Rotation by `angle` (radians, right-handed) about the unit axis `a`.
glm::dmat3 rotationAbout(const glm::dvec3 &a, double angle) {
    const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
    // Rodrigues, column-major.
    return glm::dmat3(glm::dvec3(t * a.x * a.x + c, t * a.x * a.y + s * a.z, t * a.x * a.z - s * a.y),
                      glm::dvec3(t * a.x * a.y - s * a.z, t * a.y * a.y + c, t * a.y * a.z + s * a.x),
                      glm::dvec3(t * a.x * a.z + s * a.y, t * a.y * a.z - s * a.x, t * a.z * a.z + c));
}

glm::dvec3 anyPerpendicular(const glm::dvec3 &n) {
    const glm::dvec3 helper = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    return glm::normalize(glm::cross(n, helper));
}

double ringRadius(const GizmoShape &shape) {
    if (shape.decl.kind == GizmoDecl::Kind::Box)
        return 1.25 * std::max(shape.halfExtent.x, std::max(shape.halfExtent.y, shape.halfExtent.z));
    return shape.size;
}

/// The ring's grab point: toward the viewer's upper right, off the centre on screen.
glm::dvec3 ringGrabPoint(const GizmoShape &shape, int axis, const GizmoView &view) {
    const glm::dvec3 a = shape.axes[axis];
    const glm::dmat3 sceneFromCamera(view.camera.sceneFromCamera());
    const glm::dvec3 want = glm::normalize(sceneFromCamera[0] + 0.6 * sceneFromCamera[1] + 0.4 * sceneFromCamera[2]);
    glm::dvec3 inPlane = want - glm::dot(want, a) * a;
    if (!(glm::length(inPlane) > 1e-6)) inPlane = anyPerpendicular(a);
    return shape.center + ringRadius(shape) * glm::normalize(inPlane);
}

/// The points of ring `axis` (closed: the last equals the first).
std::vector<glm::dvec3> ringPoints(const GizmoShape &shape, int axis) {
    const glm::dvec3 u = shape.axes[(axis + 1) % 3], v = shape.axes[(axis + 2) % 3];
    const double r = ringRadius(shape);
    std::vector<glm::dvec3> points;
    for (int i = 0; i <= kRingSegments; ++i) {
        const double angle = 2.0 * 3.14159265358979323846 * double(i) / kRingSegments;
        points.push_back(shape.center + r * (std::cos(angle) * u + std::sin(angle) * v));
    }
    return points;
}

/// A scene segment in framebuffer pixels, cut at a plane just in front of the eye.
std::optional<std::array<glm::vec2, 2>> projectSegment(const GizmoView &view, glm::dvec3 p, glm::dvec3 q) {
    const glm::dvec3 eye(view.camera.eye()), forward = view.forward();
    const double near = 1e-3 * std::max(glm::length(glm::dvec3(view.camera.target()) - eye), 1e-9);
    double dp = glm::dot(p - eye, forward), dq = glm::dot(q - eye, forward);
    if (dp < near && dq < near) return std::nullopt;
    if (dp < near) p = p + (q - p) * ((near - dp) / (dq - dp));
    else if (dq < near) q = q + (p - q) * ((near - dq) / (dp - dq));
    const auto a = view.pixelFromScene(p), b = view.pixelFromScene(q);
    if (!a || !b) return std::nullopt;
    return std::array<glm::vec2, 2>{*a, *b};
}

void addPolyline(GizmoDrawing::Line &line, const GizmoView &view, const std::vector<glm::dvec3> &points) {
    for (size_t i = 0; i + 1 < points.size(); ++i)
        if (const auto segment = projectSegment(view, points[i], points[i + 1])) line.segments.push_back(*segment);
}

float distanceToSegment(const glm::vec2 &p, const glm::vec2 &a, const glm::vec2 &b) {
    const glm::vec2 ab = b - a;
    const float lengthSquared = glm::dot(ab, ab);
    const float t = lengthSquared > 0.f ? std::clamp(glm::dot(p - a, ab) / lengthSquared, 0.f, 1.f) : 0.f;
    return glm::length(p - (a + t * ab));
}

GizmoDrawing::State stateOf(const GizmoHandle &handle, const std::optional<GizmoHandle> &hovered,
                            const std::optional<GizmoHandle> &active) {
    if (active && active->sameGrip(handle)) return GizmoDrawing::State::Active;
    if (hovered && hovered->sameGrip(handle)) return GizmoDrawing::State::Hovered;
    return GizmoDrawing::State::Normal;
}

} // namespace

// --- the view ---------------------------------------------------------------------------------------

glm::dvec3 GizmoView::forward() const { return -glm::dvec3(camera.sceneFromCamera()[2]); }

std::optional<glm::vec2> GizmoView::pixelFromScene(const glm::dvec3 &scene) const {
    // The inverse of Camera::generateRay.
    const glm::dvec3 q = glm::transpose(glm::dmat3(camera.sceneFromCamera())) * (scene - glm::dvec3(camera.eye()));
    const double depth = -q.z;
    if (!(depth > 0.0)) return std::nullopt;
    const double tanHalf = tanHalfFov(camera), aspect = double(viewSize.x) / double(viewSize.y);
    const double sx = q.x / depth / (tanHalf * aspect), sy = q.y / depth / tanHalf;
    const glm::dvec2 pixel((sx + 1.0) * 0.5 * viewSize.x, (1.0 - sy) * 0.5 * viewSize.y);
    if (!std::isfinite(pixel.x) || !std::isfinite(pixel.y) || std::abs(pixel.x) > 1e7 || std::abs(pixel.y) > 1e7)
        return std::nullopt;
    return glm::vec2(pixel);
}

std::pair<glm::dvec3, glm::dvec3> GizmoView::ray(const glm::vec2 &pixel) const {
    const Ray r = camera.generateRay(pixel.x, pixel.y, viewSize.x, viewSize.y);
    return {glm::dvec3(r.origin), glm::normalize(glm::dvec3(r.direction))};
}

double GizmoView::sceneLengthPerPixel(const glm::dvec3 &scene) const {
    const double depth = std::max(glm::dot(scene - glm::dvec3(camera.eye()), forward()), 1e-9);
    return depth * 2.0 * tanHalfFov(camera) / double(viewSize.y);
}

// --- handles and drawing -------------------------------------------------------------------------------

std::vector<GizmoHandle> gizmoHandles(const GizmoShape &shape, int gizmo, const GizmoView &view) {
    std::vector<GizmoHandle> handles;
    const auto add = [&](GizmoHandle::Kind kind, const glm::dvec3 &anchor, int axis = 0, int side = 1) {
        const auto pixel = view.pixelFromScene(anchor);
        if (pixel) handles.push_back({kind, gizmo, axis, side, anchor, *pixel});
    };
    const glm::dvec3 forward = view.forward();
    const GizmoDecl::Kind kind = shape.decl.kind;
    if (kind != GizmoDecl::Kind::Arrow && kind != GizmoDecl::Kind::Rings) add(GizmoHandle::Kind::Center, shape.center);
    if (kind == GizmoDecl::Kind::Box)
        for (int axis = 0; axis < 3; ++axis) {
            if (std::abs(glm::dot(shape.axes[axis], forward)) > kAxisAlongView) continue;
            for (int side : {1, -1})
                add(GizmoHandle::Kind::Face, shape.center + double(side) * shape.halfExtent[axis] * shape.axes[axis], axis,
                    side);
        }
    if (kind == GizmoDecl::Kind::Sphere)
        add(GizmoHandle::Kind::Radius, shape.center + shape.radius * glm::dvec3(view.camera.sceneFromCamera()[0]));
    if (kind == GizmoDecl::Kind::Plane || kind == GizmoDecl::Kind::Arrow)
        add(GizmoHandle::Kind::Normal, shape.center + shape.size * shape.normal);
    if (kind == GizmoDecl::Kind::Rings || (kind == GizmoDecl::Kind::Box && !shape.decl.rotation.empty()))
        for (int axis = 0; axis < 3; ++axis) add(GizmoHandle::Kind::Ring, ringGrabPoint(shape, axis, view), axis);
    return handles;
}

GizmoDrawing gizmoDrawing(const GizmoShape &shape, int gizmo, const GizmoView &view,
                          const std::optional<GizmoHandle> &hovered, const std::optional<GizmoHandle> &active) {
    GizmoDrawing drawing;
    const std::vector<GizmoHandle> handles = gizmoHandles(shape, gizmo, view);
    const auto stateOfKind = [&](GizmoHandle::Kind kind, int axis) {
        return stateOf(GizmoHandle{kind, gizmo, axis, 1}, hovered, active);
    };
    const GizmoDecl::Kind kind = shape.decl.kind;
    if (kind == GizmoDecl::Kind::Box) {
        GizmoDrawing::Line edges;
        const auto corner = [&](int i) {
            glm::dvec3 p = shape.center;
            for (int axis = 0; axis < 3; ++axis)
                p += ((i >> axis) & 1 ? 1.0 : -1.0) * shape.halfExtent[axis] * shape.axes[axis];
            return p;
        };
        for (int i = 0; i < 8; ++i)
            for (int axis = 0; axis < 3; ++axis)
                if (!((i >> axis) & 1))
                    if (const auto segment = projectSegment(view, corner(i), corner(i | (1 << axis))))
                        edges.segments.push_back(*segment);
        drawing.lines.push_back(std::move(edges));
    }
    if (kind == GizmoDecl::Kind::Rings || (kind == GizmoDecl::Kind::Box && !shape.decl.rotation.empty()))
        for (int axis = 0; axis < 3; ++axis) {
            GizmoDrawing::Line ring;
            ring.axis = axis;
            ring.state = stateOfKind(GizmoHandle::Kind::Ring, axis);
            addPolyline(ring, view, ringPoints(shape, axis));
            drawing.lines.push_back(std::move(ring));
        }
    if (kind == GizmoDecl::Kind::Sphere) {
        // The outline as the viewer sees it: a circle in the camera-facing plane.
        GizmoShape facing = shape;
        const glm::dmat3 sceneFromCamera(view.camera.sceneFromCamera());
        facing.axes = glm::dmat3(sceneFromCamera[2], sceneFromCamera[0], sceneFromCamera[1]);
        facing.size = shape.radius;
        facing.decl.kind = GizmoDecl::Kind::Rings;
        GizmoDrawing::Line outline;
        outline.state = stateOfKind(GizmoHandle::Kind::Radius, 0);
        addPolyline(outline, view, ringPoints(facing, 0));
        drawing.lines.push_back(std::move(outline));
    }
    if (kind == GizmoDecl::Kind::Plane) {
        const glm::dvec3 u = anyPerpendicular(shape.normal), v = glm::cross(shape.normal, u);
        const double half = 0.75 * shape.size;
        GizmoDrawing::Line square;
        addPolyline(square, view,
                    {shape.center + half * (u + v), shape.center + half * (v - u), shape.center - half * (u + v),
                     shape.center + half * (u - v), shape.center + half * (u + v)});
        drawing.lines.push_back(std::move(square));
    }
    if (kind == GizmoDecl::Kind::Plane || kind == GizmoDecl::Kind::Arrow) {
        GizmoDrawing::Line shaft;
        shaft.state = stateOfKind(GizmoHandle::Kind::Normal, 0);
        addPolyline(shaft, view, {shape.center, shape.center + shape.size * shape.normal});
        drawing.lines.push_back(std::move(shaft));
    }
    for (const GizmoHandle &handle : handles) {
        const bool colouredByAxis = handle.kind == GizmoHandle::Kind::Face || handle.kind == GizmoHandle::Kind::Ring;
        drawing.dots.push_back({handle.pixel, colouredByAxis ? handle.axis : -1, stateOf(handle, hovered, active)});
    }
    return drawing;
}

// --- hit test ----------------------------------------------------------------------------------------------

std::optional<GizmoHandle> gizmoHandleAt(const std::vector<GizmoShape> &shapes, const GizmoView &view,
                                         const glm::vec2 &pixel, float tolerance) {
    std::optional<GizmoHandle> best;
    float bestDistance = tolerance;
    double bestDepth = std::numeric_limits<double>::infinity();
    const glm::dvec3 eye(view.camera.eye()), forward = view.forward();
    // Dots first: a handle's dot wins over a ring passing near it.
    for (size_t i = 0; i < shapes.size(); ++i)
        for (const GizmoHandle &handle : gizmoHandles(shapes[i], int(i), view)) {
            const float distance = glm::length(handle.pixel - pixel);
            const double depth = glm::dot(handle.anchor - eye, forward);
            // Nearer on screen wins; at the same distance, the one nearer the eye.
            if (distance < bestDistance || (distance == bestDistance && best && depth < bestDepth)) {
                best = handle, bestDistance = distance, bestDepth = depth;
            }
        }
    if (best) return best;
    bestDistance = tolerance;
    for (size_t i = 0; i < shapes.size(); ++i) {
        const GizmoShape &shape = shapes[i];
        if (shape.decl.kind != GizmoDecl::Kind::Rings &&
            !(shape.decl.kind == GizmoDecl::Kind::Box && !shape.decl.rotation.empty()))
            continue;
        for (int axis = 0; axis < 3; ++axis) {
            GizmoDrawing::Line ring;
            addPolyline(ring, view, ringPoints(shape, axis));
            for (const auto &segment : ring.segments) {
                const float distance = distanceToSegment(pixel, segment[0], segment[1]);
                if (distance >= bestDistance) continue;
                bestDistance = distance;
                const glm::dvec3 anchor = ringGrabPoint(shape, axis, view);
                best = GizmoHandle{GizmoHandle::Kind::Ring, int(i), axis, 1, anchor, pixel};
            }
        }
    }
    return best;
}

// --- drags ---------------------------------------------------------------------------------------------------

GizmoShape dragGizmo(const GizmoShape &start, const GizmoHandle &handle, const GizmoView &view,
                     const glm::vec2 &pressPixel, const glm::vec2 &pixel, KeyModifier modifiers, double minimumSize) {
    GizmoShape shape = start;
    // Plain variables, not structured bindings: the lambdas below capture them (clang 14
    // cannot capture a binding).
    const std::pair<glm::dvec3, glm::dvec3> pressRay = view.ray(pressPixel), pointerRay = view.ray(pixel);
    const glm::dvec3 o0 = pressRay.first, d0 = pressRay.second, o1 = pointerRay.first, d1 = pointerRay.second;
    const glm::dvec3 forward = view.forward();
    const bool shift = hasModifier(modifiers, KeyModifier::Shift);
    const auto alongLine = [&](const glm::dvec3 &P, const glm::dvec3 &a) -> std::optional<double> {
        const auto t0 = closestOnLine(P, a, o0, d0), t1 = closestOnLine(P, a, o1, d1);
        if (!t0 || !t1) return std::nullopt;
        return *t1 - *t0;
    };
    const auto inViewPlane = [&](const glm::dvec3 &P) -> std::optional<glm::dvec3> {
        const auto h0 = onPlane(P, forward, o0, d0), h1 = onPlane(P, forward, o1, d1);
        if (!h0 || !h1) return std::nullopt;
        return *h1 - *h0;
    };
    switch (handle.kind) {
    case GizmoHandle::Kind::Face: {
        const int axis = handle.axis;
        const glm::dvec3 a = start.axes[axis];
        const double side = handle.side > 0 ? 1.0 : -1.0;
        const glm::dvec3 face = start.center + side * start.halfExtent[axis] * a;
        auto delta = alongLine(face, a);
        if (!delta) break;
        // Past the axis's vanishing point on screen the closest point of the line jumps to its
        // other end: the pointer's motion along the axis's image decides the direction.
        const auto facePixel = view.pixelFromScene(face), ahead = view.pixelFromScene(face + 1e-3 * start.size * a);
        if (facePixel && ahead && glm::length(*ahead - *facePixel) > 0.f) {
            const double onScreen = glm::dot(pixel - pressPixel, glm::normalize(*ahead - *facePixel));
            if (onScreen * *delta < 0.0) {
                if (onScreen * side > 0.0) break;         // outward beyond the horizon: as far as it went
                *delta = -side * std::numeric_limits<double>::infinity(); // inward: onto the opposite face
            }
        }
        // Coordinates along the axis, from the centre: the dragged face f, the fixed face g.
        const double g = -side * start.halfExtent[axis];
        double f = side * start.halfExtent[axis] + *delta;
        f = side > 0 ? std::max(f, g + minimumSize) : std::min(f, g - minimumSize); // faces never cross
        shape.halfExtent[axis] = 0.5 * std::abs(f - g);
        shape.center = start.center + 0.5 * (f + g) * a;
        break;
    }
    case GizmoHandle::Kind::Center: {
        if (shift && start.decl.kind == GizmoDecl::Kind::Box) {
            // Along the box axis whose screen image runs most like the pointer's motion.
            const glm::vec2 motion = pixel - pressPixel;
            const auto centerPixel = view.pixelFromScene(start.center);
            int bestAxis = -1;
            float bestAlignment = -1.f;
            for (int axis = 0; axis < 3 && centerPixel; ++axis) {
                const auto tip = view.pixelFromScene(start.center + start.size * start.axes[axis]);
                if (!tip || glm::length(*tip - *centerPixel) < 1e-3f || glm::length(motion) == 0.f) continue;
                const float alignment = std::abs(glm::dot(glm::normalize(*tip - *centerPixel), glm::normalize(motion)));
                if (alignment > bestAlignment) bestAlignment = alignment, bestAxis = axis;
            }
            if (bestAxis < 0) break;
            if (const auto delta = alongLine(start.center, start.axes[bestAxis]))
                shape.center = start.center + *delta * start.axes[bestAxis];
        } else if (shift) {
            // Along the view direction: pointer up moves it away.
            shape.center = start.center + double(pressPixel.y - pixel.y) * view.sceneLengthPerPixel(start.center) * forward;
        } else if (const auto delta = inViewPlane(start.center)) {
            shape.center = start.center + *delta;
        }
        break;
    }
    case GizmoHandle::Kind::Ring: {
        const int axis = handle.axis;
        const glm::dvec3 a = start.axes[axis];
        const double radius = ringRadius(start);
        double angle = 0.0;
        if (std::abs(glm::dot(d0, a)) < kRingEdgeOn) {
            // Edge-on, the ring is a line on screen: the pointer moves its near side along it,
            // measured on the camera-facing plane through the centre.
            const auto motion = inViewPlane(start.center);
            glm::dvec3 towardEye = -(forward - glm::dot(forward, a) * a);
            if (!motion || !(glm::length(towardEye) > 1e-9)) break;
            towardEye = glm::normalize(towardEye);
            angle = glm::dot(*motion, glm::cross(a, towardEye)) / radius;
        } else {
            const auto h0 = onPlane(start.center, a, o0, d0), h1 = onPlane(start.center, a, o1, d1);
            if (!h0 || !h1) break;
            const glm::dvec3 v0 = *h0 - start.center, v1 = *h1 - start.center;
            if (!(glm::length(v0) > 0.0) || !(glm::length(v1) > 0.0)) break;
            angle = std::atan2(glm::dot(glm::cross(v0, v1), a), glm::dot(v0, v1));
        }
        shape.axes = rotationAbout(a, angle) * start.axes;
        // Keep the axes orthonormal against rounding drift over many drags.
        const glm::dvec3 x = glm::normalize(shape.axes[0]);
        const glm::dvec3 y = glm::normalize(shape.axes[1] - glm::dot(shape.axes[1], x) * x);
        shape.axes = glm::dmat3(x, y, glm::cross(x, y));
        break;
    }
    case GizmoHandle::Kind::Radius: {
        // The radius follows the pointer's motion along the direction it was grabbed in, so a
        // pointer dragged through the centre shrinks the sphere to its minimum, not back out.
        const auto h0 = onPlane(start.center, forward, o0, d0), h1 = onPlane(start.center, forward, o1, d1);
        if (!h0 || !h1) break;
        const glm::dvec3 outward = glm::length(handle.anchor - start.center) > 0.0
                                       ? glm::normalize(handle.anchor - start.center)
                                       : glm::dvec3(view.camera.sceneFromCamera()[0]);
        shape.radius = std::max(start.radius + glm::dot(*h1 - *h0, outward), minimumSize);
        break;
    }
    case GizmoHandle::Kind::Normal: {
        // The tip on the sphere of the arrow's length: the ray's near hit, else (the pointer
        // beside the sphere) the point of the sphere's outline nearest the ray.
        const glm::dvec3 oc = o1 - start.center;
        const double b = glm::dot(oc, d1), c = glm::dot(oc, oc) - start.size * start.size;
        const double discriminant = b * b - c;
        glm::dvec3 tip;
        if (discriminant >= 0.0 && -b - std::sqrt(discriminant) > 0.0) {
            tip = o1 + (-b - std::sqrt(discriminant)) * d1;
        } else {
            tip = o1 + std::max(-b, 0.0) * d1; // closest point of the ray to the centre
        }
        const glm::dvec3 direction = tip - start.center;
        if (glm::length(direction) > 0.0) shape.normal = glm::normalize(direction);
        break;
    }
    }
    return shape;
}

} // namespace mvcl
